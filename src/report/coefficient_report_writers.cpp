// Writers of the coefficient report: Markdown and HTML share one document (headings, paragraphs,
// lists, tables) built once; CSV and JSON carry the numbers at full precision (shortest text that
// reads back to the same double).
#include <charconv>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "base/text_format.hpp"
#include "report/svg_plot.hpp"
#include "skyspec/coefficient_report.hpp"
#include "skyspec/error.hpp"
#include "skyspec/units.hpp"

namespace skyspec {
namespace {

constexpr double kPpmPerPpv = 1.0e6;

// ---- numbers --------------------------------------------------------------------------------

/// Shortest decimal text that reads back to exactly v (C++17 to_chars); "" (an empty CSV cell) for
/// a value the report does not have (NaN: ozone beyond its table).
std::string exact(double v) {
  if (!std::isfinite(v)) return "";
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string sig(double v, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

std::string sci(double v, int digits = 5) {
  if (!std::isfinite(v)) return "n/a";  // a value the report does not have (ozone beyond its table)
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*e", digits - 1, v);
  return buf;
}

std::string signed_percent(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%+.3f", v);
  return buf;
}

std::string altitude_label(double z_m) { return format_number(z_m) + " m"; }

// ---- a small document model shared by Markdown and HTML ------------------------------------

struct Block {
  enum class Kind { Heading, Paragraph, List, Table } kind;
  int level = 2;
  std::string text;
  std::vector<std::string> items;              ///< list items, or table headers
  std::vector<std::vector<std::string>> rows;  ///< table rows
};

struct Document {
  std::vector<Block> blocks;
  void heading(int level, std::string t) { blocks.push_back({Block::Kind::Heading, level, std::move(t), {}, {}}); }
  void paragraph(std::string t) { blocks.push_back({Block::Kind::Paragraph, 0, std::move(t), {}, {}}); }
  void list(std::vector<std::string> items) { blocks.push_back({Block::Kind::List, 0, {}, std::move(items), {}}); }
  void table(std::vector<std::string> headers, std::vector<std::vector<std::string>> rows) {
    blocks.push_back({Block::Kind::Table, 0, {}, std::move(headers), std::move(rows)});
  }
};

std::string composition_text(const AirComposition& c) {
  return "N2 " + sig(c.n2_percent) + " %, O2 " + sig(c.o2_percent) + " %, Ar " + sig(c.ar_percent) + " %, CO2 " +
         sig(c.co2_percent, 4) + " % by volume";
}

Document build_document(const CoefficientReport& r) {
  Document d;
  d.heading(1, "skyspec coefficient derivation report");
  d.paragraph("skyspec " + r.skyspec_version + ". Atmosphere: " + (r.origin.empty() ? "as given" : r.origin) +
              ". Every number below is computed by the engine that renders (the same atmosphere model, density "
              "profiles and column integrals).");

  d.heading(2, "Inputs");
  std::vector<std::string> inputs;
  inputs.push_back("Wavelengths: " + std::to_string(r.wavelengths_nm.size()) + " from " +
                   sig(r.wavelengths_nm.front()) + " to " + sig(r.wavelengths_nm.back()) + " nm.");
  if (r.gas == ScatteringGas::CarbonDioxide) {
    inputs.push_back(
        "Scattering gas: pure CO2 (refractive index and King factor of Sneep & Ubachs 2005; the "
        "refractive-index formula and the CO2 content of air do not apply).");
  } else {
    inputs.push_back("Refractive index: " + describe(r.formula) + ".");
    inputs.push_back("CO2: " + sig(r.co2_ppv * kPpmPerPpv) +
                     " ppm; air composition for the King factor: " + composition_text(r.composition) + ".");
  }
  inputs.push_back(
      std::string("Rayleigh coefficients: ") +
      (r.rayleigh_derived ? "derived (beta = sigma N)" : "typed in (atmosphere.rayleigh.source = \"fixed\")") +
      "; density profile: " + r.profile_description + "; top of the atmosphere " + format_number(r.top_altitude_m) +
      " m.");
  if (r.mie_enabled && !r.mie_opac_components.empty()) {
    std::string parts;
    for (const auto& [name, n] : r.mie_opac_components) parts += (parts.empty() ? "" : ", ") + name + " " + sig(n);
    inputs.push_back("Aerosols: OPAC components by Lorenz-Mie theory (atmosphere.mie.model = \"opac\"): " + parts +
                     " particles per cm^3 at altitude 0, relative humidity " +
                     sig(r.mie_opac_relative_humidity_percent) + " %; profile: " + r.mie_profile_description + ".");
  } else if (r.mie_enabled && r.mie_tabulated)
    inputs.push_back("Aerosols: beta_sca = " + sig(r.mie_scattering_at_reference_per_m) + " m^-1 at " +
                     sig(r.mie_reference_wavelength_nm) +
                     " nm and altitude 0, spectral shape, albedo and g from the "
                     "scene's aerosol tables; profile: " +
                     r.mie_profile_description + ".");
  else if (r.mie_enabled)
    inputs.push_back("Aerosols: beta_sca = " + sig(r.mie_scattering_at_reference_per_m) + " m^-1 at " +
                     sig(r.mie_reference_wavelength_nm) + " nm and altitude 0, Angstrom exponent " +
                     sig(r.mie_angstrom_exponent) + ", extinction = " + sig(r.mie_extinction_to_scattering) +
                     " x scattering; profile: " + r.mie_profile_description + ".");
  else
    inputs.push_back("Aerosols: none (atmosphere.mie.enabled = false).");
  if (r.ozone_enabled)
    inputs.push_back("Ozone: " + sig(r.ozone_column_DU) + " DU, peak number density " +
                     sci(r.ozone_peak_number_density_per_m3, 5) + " m^-3; profile: " + r.ozone_profile_description +
                     ".");
  for (const auto& m : r.media)
    inputs.push_back("Also in the air: " + m.name + "; profile: " + m.profile_description +
                     (m.region_description.empty() ? "" : "; " + m.region_description) + ".");
  std::string alts;
  for (const auto& l : r.levels) alts += (alts.empty() ? "" : ", ") + altitude_label(l.altitude_m);
  inputs.push_back("Altitudes: " + alts + ".");
  if (r.conditions)
    inputs.push_back("Conditions: P = " + sig(r.conditions->air.pressure_Pa) + " Pa (" +
                     sig(r.conditions->air.pressure_Pa / 100.0) + " hPa), T = " + sig(r.conditions->air.temperature_K) +
                     " K.");
  inputs.push_back("Latitude for gravity (hydrostatic columns): " + sig(r.latitude_deg) + " degrees.");
  d.list(inputs);

  d.heading(2, "Formulas");
  std::vector<std::vector<std::string>> frows;
  for (const auto& f : r.formulas) frows.push_back({f.quantity, "`" + f.formula + "`", f.units, f.source});
  d.table({"quantity", "formula", "units", "source"}, frows);

  d.heading(2, "Rayleigh derivation per wavelength");
  if (r.gas == ScatteringGas::CarbonDioxide)
    d.paragraph(
        "Pure CO2: n_s - 1 and F(CO2) of Sneep & Ubachs 2005 at 288.15 K and 101325 Pa (the N2 and O2 "
        "columns do not apply); sigma paired with N_s = 2.546899e25 m^-3. sigma does not depend on "
        "pressure or temperature.");
  else
    d.paragraph("n_s - 1 from " + to_string(r.formula) + " at the formula's own CO2 and corrected to " +
                sig(r.co2_ppv * kPpmPerPpv) +
                " ppm; King factors of N2 and O2 (Bates 1984), Ar 1.00, CO2 1.15, and "
                "of the air mix; sigma paired with N_s = 2.546899e25 m^-3. sigma does not depend on pressure or "
                "temperature.");
  std::vector<std::vector<std::string>> drows;
  for (const auto& s : r.derivation)
    drows.push_back({sig(s.lambda_nm), sci(s.refractivity_ref, 7), sci(s.refractivity, 7), format_fixed(s.king_n2, 5),
                     format_fixed(s.king_o2, 5), format_fixed(s.king_factor, 5), sci(s.cross_section_m2, 5)});
  d.table({"lambda (nm)", "n_s - 1 (formula)", "n_s - 1 (CO2-corrected)", "F(N2)", "F(O2)", "F(air)", "sigma (m^2)"},
          drows);

  d.heading(2, "Number density at each altitude");
  std::vector<std::vector<std::string>> nrows;
  for (const auto& l : r.levels)
    nrows.push_back({altitude_label(l.altitude_m), r.rayleigh_derived ? sci(l.rayleigh_number_density_per_m3, 6) : "-",
                     l.number_density_origin});
  d.table({"altitude", "N (m^-3)", "how it was obtained"}, nrows);

  for (const auto& l : r.levels) {
    d.heading(2, "Coefficients and vertical optical depth at " + altitude_label(l.altitude_m));
    d.paragraph(
        "beta at this altitude (m^-1); tau: vertical optical depth from this altitude to the top of the "
        "atmosphere (" +
        format_number(r.top_altitude_m) + " m), integrated through the density profiles.");
    std::vector<std::string> headers{"lambda (nm)", "beta_R (m^-1)", "tau_R"};
    if (r.mie_enabled)
      for (const char* h : {"beta_M sca (m^-1)", "beta_M ext (m^-1)", "tau_M"}) headers.push_back(h);
    if (r.ozone_enabled)
      for (const char* h : {"sigma_O3 (m^2)", "beta_O3 abs (m^-1)", "tau_O3"}) headers.push_back(h);
    for (const auto& m : r.media)
      for (const std::string& h : {"beta_" + m.name + " sca (m^-1)", "beta_" + m.name + " ext (m^-1)", "tau_" + m.name})
        headers.push_back(h);
    headers.push_back("tau total");
    std::vector<std::vector<std::string>> rows;
    for (size_t i = 0; i < r.wavelengths_nm.size(); ++i) {
      std::vector<std::string> row{sig(r.wavelengths_nm[i]), sci(l.rayleigh_scattering_per_m[i]),
                                   sci(l.rayleigh_optical_depth[i])};
      if (r.mie_enabled)
        for (double v : {l.mie_scattering_per_m[i], l.mie_extinction_per_m[i], l.mie_optical_depth[i]})
          row.push_back(sci(v));
      if (r.ozone_enabled)
        for (double v : {r.ozone_cross_section_m2[i], l.ozone_absorption_per_m[i], l.ozone_optical_depth[i]})
          row.push_back(sci(v));
      for (const auto& m : l.media)
        for (double v : {m.scattering_per_m[i], m.extinction_per_m[i], m.optical_depth[i]}) row.push_back(sci(v));
      row.push_back(sci(l.total_optical_depth[i]));
      rows.push_back(row);
    }
    d.table(headers, rows);
  }

  if (r.conditions) {
    const auto& c = *r.conditions;
    d.heading(2, "Air at " + sig(c.air.pressure_Pa / 100.0) + " hPa and " + sig(c.air.temperature_K) + " K");
    d.paragraph("N = P / (k T) = " + sig(c.air.pressure_Pa) + " Pa / (1.380649e-23 J/K x " + sig(c.air.temperature_K) +
                " K) = " + sci(c.number_density_per_m3, 6) + " m^-3, " + format_fixed(c.density_ratio, 5) +
                " x standard air. The cross-section is the same as above; (n - 1) scales with N. tau above: the "
                "hydrostatic column above the level where the pressure is P, sigma P N_A / (m_a g) = sigma x " +
                sci(c.column_molecules_per_m2, 6) + " m^-2, with g = " + format_fixed(c.column_gravity_m_per_s2, 5) +
                " m s^-2 at the mass-weighted altitude of the column above " + format_fixed(c.pressure_altitude_m, 0) +
                " m (the U.S. Standard Atmosphere 1976 altitude of that pressure).");
    std::vector<std::vector<std::string>> rows;
    for (size_t i = 0; i < r.wavelengths_nm.size(); ++i)
      rows.push_back({sig(r.wavelengths_nm[i]), sci(c.refractivity[i], 6), sci(c.rayleigh_scattering_per_m[i]),
                      sci(c.rayleigh_optical_depth_above[i])});
    d.table({"lambda (nm)", "n - 1 at (P, T)", "beta_R (m^-1)", "tau_R above"}, rows);
  }

  d.heading(2, "Checked against published values");
  d.paragraph(
      "Each comparison is computed at the published conditions (not those of the atmosphere above). "
      "Difference = 100 (skyspec / published - 1) %.");
  for (const auto& c : r.references) {
    d.heading(3, c.title);
    d.list({"Published conditions: " + c.conditions + ".", "Source: " + c.source + ".", "skyspec: " + c.method + ".",
            "Largest |difference|: " + format_fixed(c.max_abs_difference_percent, 3) + " %."});
    std::vector<std::vector<std::string>> rows;
    for (const auto& row : c.rows)
      rows.push_back(
          {sig(row.wavelength_nm), sig(row.published, 6), sig(row.skyspec, 6), signed_percent(row.difference_percent)});
    d.table({"lambda (nm)", "published: " + c.quantity, "skyspec", "difference (%)"}, rows);
    d.paragraph(c.explanation);
  }

  d.heading(2, "Notes");
  d.list(r.notes);
  return d;
}

std::string render_markdown(const Document& d) {
  std::ostringstream s;
  for (const auto& b : d.blocks) {
    switch (b.kind) {
      case Block::Kind::Heading:
        s << std::string(static_cast<size_t>(b.level), '#') << ' ' << b.text << "\n\n";
        break;
      case Block::Kind::Paragraph:
        s << b.text << "\n\n";
        break;
      case Block::Kind::List:
        for (const auto& item : b.items) s << "- " << item << "\n";
        s << "\n";
        break;
      case Block::Kind::Table:
        s << '|';
        for (const auto& h : b.items) s << ' ' << markdown_cell(h) << " |";
        s << "\n|";
        for (size_t i = 0; i < b.items.size(); ++i) s << " --- |";
        s << "\n";
        for (const auto& row : b.rows) {
          s << '|';
          for (const auto& cell : row) s << ' ' << markdown_cell(cell) << " |";
          s << "\n";
        }
        s << "\n";
        break;
    }
  }
  return s.str();
}

/// Markdown `code` spans become <code> in HTML.
std::string html_inline(const std::string& text) {
  std::string esc = svg::escape(text), out;
  bool open = false;
  for (char ch : esc) {
    if (ch == '`') {
      out += open ? "</code>" : "<code>";
      open = !open;
    } else {
      out += ch;
    }
  }
  if (open) out += "</code>";
  return out;
}

// ---- plots --------------------------------------------------------------------------------

const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"};

std::string colour(size_t i) { return kPalette[i % (sizeof kPalette / sizeof kPalette[0])]; }

const ReferenceComparison* find_reference(const CoefficientReport& r, const std::string& id) {
  for (const auto& c : r.references)
    if (c.id == id) return &c;
  return nullptr;
}

std::vector<std::string> plots(const CoefficientReport& r) {
  std::vector<std::string> out;
  const auto& x = r.wavelengths_nm;
  {
    std::vector<svg::Series> s;
    size_t k = 0;
    for (const auto& l : r.levels) {
      s.push_back(
          {"Rayleigh, " + altitude_label(l.altitude_m), x, l.rayleigh_scattering_per_m, colour(k++), false, false});
      if (r.mie_enabled)
        s.push_back(
            {"aerosol sca, " + altitude_label(l.altitude_m), x, l.mie_scattering_per_m, colour(k++), false, true});
    }
    if (r.conditions)
      s.push_back({"Rayleigh at " + sig(r.conditions->air.pressure_Pa / 100.0) + " hPa, " +
                       sig(r.conditions->air.temperature_K) + " K",
                   x, r.conditions->rayleigh_scattering_per_m, colour(k++), false, true});
    if (const auto* seed = find_reference(r, "seed_constants")) {
      svg::Series pts{"seed tutorial constants", {}, {}, "#000000", true, false};
      for (const auto& row : seed->rows) {
        pts.x.push_back(row.wavelength_nm);
        pts.y.push_back(row.published);
      }
      s.push_back(pts);
    }
    out.push_back(svg::line_plot(
        {"Volume scattering coefficient beta(lambda)", "wavelength (nm)", "beta (m^-1)", true, true}, s));
  }
  {
    std::vector<double> f, n2, o2;
    for (const auto& st : r.derivation) {
      f.push_back(st.king_factor);
      n2.push_back(st.king_n2);
      o2.push_back(st.king_o2);
    }
    std::vector<svg::Series> s{{"F(air), " + sig(r.co2_ppv * kPpmPerPpv) + " ppm CO2", x, f, colour(0), false, false},
                               {"F(N2), Bates 1984", x, n2, colour(1), false, true},
                               {"F(O2), Bates 1984", x, o2, colour(2), false, true}};
    if (const auto* b = find_reference(r, "bucholtz1995_king_factor")) {
      svg::Series pts{"Bucholtz 1995 (air, 300 ppm)", {}, {}, "#000000", true, false};
      for (const auto& row : b->rows) {
        pts.x.push_back(row.wavelength_nm);
        pts.y.push_back(row.published);
      }
      s.push_back(pts);
    }
    out.push_back(
        svg::line_plot({"King (depolarization) factor", "wavelength (nm)", "F (dimensionless)", false, false}, s));
  }
  {
    std::vector<svg::Series> s;
    size_t k = 0;
    for (const auto& l : r.levels) {
      s.push_back(
          {"Rayleigh from " + altitude_label(l.altitude_m), x, l.rayleigh_optical_depth, colour(k++), false, false});
      if (r.mie_enabled)
        s.push_back({"aerosol from " + altitude_label(l.altitude_m), x, l.mie_optical_depth, colour(k++), false, true});
      if (r.ozone_enabled)
        s.push_back({"ozone from " + altitude_label(l.altitude_m), x, l.ozone_optical_depth, colour(k++), false, true});
    }
    if (const auto* b = find_reference(r, "bodhaine1999_table3")) {
      svg::Series pts{"Bodhaine 1999 Table 3 (sea level)", {}, {}, "#000000", true, false};
      for (const auto& row : b->rows) {
        pts.x.push_back(row.wavelength_nm);
        pts.y.push_back(row.published);
      }
      s.push_back(pts);
    }
    out.push_back(svg::line_plot(
        {"Vertical optical depth to the top of the atmosphere", "wavelength (nm)", "optical depth", false, true}, s));
  }
  return out;
}

}  // namespace

std::string report_to_markdown(const CoefficientReport& report) { return render_markdown(build_document(report)); }

std::string report_to_html(const CoefficientReport& report) {
  const Document d = build_document(report);
  std::ostringstream s;
  s << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       "<title>skyspec coefficient derivation report</title>\n<style>\n"
       "body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;line-height:1.4}\n"
       "table{border-collapse:collapse;margin:0.5em 0 1.5em;font-size:0.85em}\n"
       "td,th{border:1px solid #bbb;padding:2px 6px;text-align:right}\n"
       "th{background:#eee}\ncode{font-size:0.95em}\nfigure{margin:1em 0}\n</style>\n</head>\n<body>\n";
  bool plots_written = false;
  for (const auto& b : d.blocks) {
    // The figures go right after the inputs, before the long tables.
    if (!plots_written && b.kind == Block::Kind::Heading && b.text == "Formulas") {
      s << "<h2>Plots</h2>\n";
      for (const auto& p : plots(report)) s << "<figure>\n" << p << "</figure>\n";
      plots_written = true;
    }
    switch (b.kind) {
      case Block::Kind::Heading:
        s << "<h" << b.level << '>' << html_inline(b.text) << "</h" << b.level << ">\n";
        break;
      case Block::Kind::Paragraph:
        s << "<p>" << html_inline(b.text) << "</p>\n";
        break;
      case Block::Kind::List:
        s << "<ul>\n";
        for (const auto& item : b.items) s << "<li>" << html_inline(item) << "</li>\n";
        s << "</ul>\n";
        break;
      case Block::Kind::Table:
        s << "<table>\n<tr>";
        for (const auto& h : b.items) s << "<th>" << html_inline(h) << "</th>";
        s << "</tr>\n";
        for (const auto& row : b.rows) {
          s << "<tr>";
          for (const auto& cell : row) s << "<td>" << html_inline(cell) << "</td>";
          s << "</tr>\n";
        }
        s << "</table>\n";
        break;
    }
  }
  s << "</body>\n</html>\n";
  return s.str();
}

std::string report_to_csv(const CoefficientReport& r) {
  std::ostringstream s;
  s << "# skyspec " << r.skyspec_version
    << " coefficient derivation report, one row per wavelength; units in the "
       "column names. The comparisons with published tables are in the JSON, Markdown and HTML formats.\n";
  s << "# atmosphere: " << r.origin << "\n";
  s << "# refractive index: " << to_string(r.formula) << ", CO2 " << exact(r.co2_ppv * kPpmPerPpv) << " ppm\n";
  for (const auto& l : r.levels)
    s << "# altitude " << exact(l.altitude_m) << " m: N = " << exact(l.rayleigh_number_density_per_m3) << " m^-3 ("
      << l.number_density_origin << ")\n";
  if (r.conditions)
    s << "# conditions: P = " << exact(r.conditions->air.pressure_Pa)
      << " Pa, T = " << exact(r.conditions->air.temperature_K)
      << " K, N = " << exact(r.conditions->number_density_per_m3) << " m^-3\n";
  s << "wavelength_nm,refractivity_formula_co2,refractivity,king_factor_n2,king_factor_o2,king_factor_air,cross_"
       "section_m2";
  for (const auto& l : r.levels) {
    const std::string z = exact(l.altitude_m) + "m";
    s << ",rayleigh_scattering_per_m_at_" << z << ",rayleigh_optical_depth_from_" << z;
    if (r.mie_enabled)
      s << ",mie_scattering_per_m_at_" << z << ",mie_extinction_per_m_at_" << z << ",mie_optical_depth_from_" << z;
    if (r.ozone_enabled) s << ",ozone_absorption_per_m_at_" << z << ",ozone_optical_depth_from_" << z;
    for (const auto& m : r.media)
      s << ',' << m.name << "_scattering_per_m_at_" << z << ',' << m.name << "_extinction_per_m_at_" << z << ','
        << m.name << "_optical_depth_from_" << z;
    s << ",total_optical_depth_from_" << z;
  }
  if (r.ozone_enabled) s << ",ozone_cross_section_m2";
  if (r.conditions)
    s << ",refractivity_at_conditions,rayleigh_scattering_per_m_at_conditions,rayleigh_optical_depth_above_conditions";
  s << "\n";
  for (size_t i = 0; i < r.wavelengths_nm.size(); ++i) {
    const auto& st = r.derivation[i];
    s << exact(st.lambda_nm) << ',' << exact(st.refractivity_ref) << ',' << exact(st.refractivity) << ','
      << exact(st.king_n2) << ',' << exact(st.king_o2) << ',' << exact(st.king_factor) << ','
      << exact(st.cross_section_m2);
    for (const auto& l : r.levels) {
      s << ',' << exact(l.rayleigh_scattering_per_m[i]) << ',' << exact(l.rayleigh_optical_depth[i]);
      if (r.mie_enabled)
        s << ',' << exact(l.mie_scattering_per_m[i]) << ',' << exact(l.mie_extinction_per_m[i]) << ','
          << exact(l.mie_optical_depth[i]);
      if (r.ozone_enabled) s << ',' << exact(l.ozone_absorption_per_m[i]) << ',' << exact(l.ozone_optical_depth[i]);
      for (const auto& m : l.media)
        s << ',' << exact(m.scattering_per_m[i]) << ',' << exact(m.extinction_per_m[i]) << ','
          << exact(m.optical_depth[i]);
      s << ',' << exact(l.total_optical_depth[i]);
    }
    if (r.ozone_enabled) s << ',' << exact(r.ozone_cross_section_m2[i]);
    if (r.conditions)
      s << ',' << exact(r.conditions->refractivity[i]) << ',' << exact(r.conditions->rayleigh_scattering_per_m[i])
        << ',' << exact(r.conditions->rayleigh_optical_depth_above[i]);
    s << "\n";
  }
  return s.str();
}

std::string report_to_json(const CoefficientReport& r) {
  using json = nlohmann::ordered_json;
  json j;
  j["report"] = "skyspec coefficient derivation";
  j["skyspec_version"] = r.skyspec_version;
  j["origin"] = r.origin;
  j["wavelength_nm"] = r.wavelengths_nm;
  j["latitude_deg"] = r.latitude_deg;
  json ray;
  ray["source"] = r.rayleigh_derived ? "derived" : "fixed";
  ray["gas"] = to_string(r.gas);
  ray["refractive_index_formula"] = to_string(r.formula);
  ray["refractive_index_description"] = describe(r.formula);
  ray["co2_ppm"] = r.co2_ppv * kPpmPerPpv;
  ray["composition_percent"] = {{"N2", r.composition.n2_percent},
                                {"O2", r.composition.o2_percent},
                                {"Ar", r.composition.ar_percent},
                                {"CO2", r.composition.co2_percent}};
  ray["standard_number_density_per_m3"] = constants::kStandardNumberDensity_per_m3;
  const DerivationColumns columns = derivation_columns(r);
  ray["refractivity_formula_co2"] = columns.refractivity_ref;
  ray["refractivity"] = columns.refractivity;
  ray["king_factor_air"] = columns.king_factor_air;
  ray["king_factor_n2"] = columns.king_factor_n2;
  ray["king_factor_o2"] = columns.king_factor_o2;
  ray["king_factor_ar"] = kKingFactorAr;
  ray["king_factor_co2"] = kKingFactorCO2;
  ray["cross_section_m2"] = columns.cross_section_m2;
  ray["profile"] = r.profile_description;
  ray["top_altitude_m"] = r.top_altitude_m;
  j["rayleigh"] = ray;
  j["mie"] = {{"enabled", r.mie_enabled},
              {"tabulated", r.mie_tabulated},
              {"scattering_per_m_at_reference", r.mie_scattering_at_reference_per_m},
              {"reference_wavelength_nm", r.mie_reference_wavelength_nm},
              {"angstrom_exponent", r.mie_angstrom_exponent},
              {"extinction_to_scattering", r.mie_extinction_to_scattering},
              {"profile", r.mie_profile_description}};
  if (!r.mie_opac_components.empty()) {
    nlohmann::json components = nlohmann::json::object();
    for (const auto& [name, n] : r.mie_opac_components) components[name + "_per_cm3"] = n;
    j["mie"]["model"] = "opac";
    j["mie"]["opac_components"] = components;
    j["mie"]["relative_humidity_percent"] = r.mie_opac_relative_humidity_percent;
  }
  if (r.ozone_enabled)
    j["ozone"] = {{"column_DU", r.ozone_column_DU},
                  {"peak_number_density_per_m3", r.ozone_peak_number_density_per_m3},
                  {"cross_section_m2", r.ozone_cross_section_m2},
                  {"profile", r.ozone_profile_description}};
  else
    j["ozone"] = nullptr;
  json media = json::array();
  for (const auto& m : r.media) {
    json entry = {{"name", m.name}, {"profile", m.profile_description}};
    if (!m.region_description.empty()) entry["region"] = m.region_description;
    media.push_back(std::move(entry));
  }
  j["media"] = media;
  json levels = json::array();
  for (const auto& l : r.levels) {
    json lj;
    lj["altitude_m"] = l.altitude_m;
    lj["number_density_per_m3"] = l.rayleigh_number_density_per_m3;
    lj["temperature_K"] = l.temperature_K ? json(*l.temperature_K) : json(nullptr);
    lj["pressure_Pa"] = l.pressure_Pa ? json(*l.pressure_Pa) : json(nullptr);
    lj["number_density_origin"] = l.number_density_origin;
    lj["rayleigh_scattering_per_m"] = l.rayleigh_scattering_per_m;
    lj["rayleigh_optical_depth"] = l.rayleigh_optical_depth;
    lj["mie_scattering_per_m"] = l.mie_scattering_per_m;
    lj["mie_extinction_per_m"] = l.mie_extinction_per_m;
    lj["mie_optical_depth"] = l.mie_optical_depth;
    lj["ozone_absorption_per_m"] = l.ozone_absorption_per_m;
    lj["ozone_optical_depth"] = l.ozone_optical_depth;
    json level_media = json::object();
    for (const auto& m : l.media)
      level_media[m.name] = {{"scattering_per_m", m.scattering_per_m},
                             {"extinction_per_m", m.extinction_per_m},
                             {"optical_depth", m.optical_depth}};
    lj["media"] = level_media;
    lj["total_optical_depth"] = l.total_optical_depth;
    levels.push_back(lj);
  }
  j["levels"] = levels;
  if (r.conditions) {
    const auto& c = *r.conditions;
    j["conditions"] = {{"pressure_Pa", c.air.pressure_Pa},
                       {"temperature_K", c.air.temperature_K},
                       {"number_density_per_m3", c.number_density_per_m3},
                       {"density_ratio", c.density_ratio},
                       {"refractivity", c.refractivity},
                       {"rayleigh_scattering_per_m", c.rayleigh_scattering_per_m},
                       {"pressure_altitude_m", c.pressure_altitude_m},
                       {"column_gravity_m_per_s2", c.column_gravity_m_per_s2},
                       {"column_molecules_per_m2", c.column_molecules_per_m2},
                       {"rayleigh_optical_depth_above", c.rayleigh_optical_depth_above}};
  } else {
    j["conditions"] = nullptr;
  }
  json formulas = json::array();
  for (const auto& f0 : r.formulas)
    formulas.push_back(
        {{"quantity", f0.quantity}, {"formula", f0.formula}, {"units", f0.units}, {"source", f0.source}});
  j["formulas"] = formulas;
  json refs = json::array();
  for (const auto& c : r.references) {
    json cj;
    cj["id"] = c.id;
    cj["title"] = c.title;
    cj["quantity"] = c.quantity;
    cj["conditions"] = c.conditions;
    cj["source"] = c.source;
    cj["method"] = c.method;
    json rows = json::array();
    for (const auto& row : c.rows)
      rows.push_back({{"wavelength_nm", row.wavelength_nm},
                      {"published", row.published},
                      {"skyspec", row.skyspec},
                      {"difference_percent", row.difference_percent}});
    cj["rows"] = rows;
    cj["max_abs_difference_percent"] = c.max_abs_difference_percent;
    cj["explanation"] = c.explanation;
    refs.push_back(cj);
  }
  j["references"] = refs;
  j["notes"] = r.notes;
  return j.dump(1) + "\n";
}

}  // namespace skyspec
