// `skyspec reference`: the Monte Carlo reference radiance (all scattering orders, with standard
// errors) in a few sky directions, optionally beside the renderer's own values.

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <filesystem>
#include "commands.hpp"
#include "progress.hpp"
#include "scene_options.hpp"
#include "text_output.hpp"

#include "base/atomic_file.hpp"
#include "base/text_format.hpp"
#include "render/irradiance.hpp"
#include "render/render_budget.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/error.hpp"
#include "skyspec/monte_carlo_reference.hpp"
#include "skyspec/render.hpp"
#include "skyspec/units.hpp"
#include "skyspec/version.hpp"

namespace skyspec::cli {
namespace {

struct ReferenceOptions {
  SceneOptions scene;
  std::vector<std::string> probes;
  long long paths = 100000;
  std::string seed = "1";  ///< text: CLI11 clamps 2^64 to 2^64 - 1 without a word
  int orders = 0;
  double sun_peak_share = 0.0;
  bool irradiance = false, compare = false, stokes = false, quiet = false, force = false;
  std::string format = "md";
  std::string out;
};

struct Checked {
  Scene scene;
  std::vector<ReferenceProbe> probes;
  ReferenceSettings settings;
};

Checked check(const ReferenceOptions& o) {
  if (o.format != "md" && o.format != "csv" && o.format != "json")
    throw InputError("--format", "\"" + o.format + "\"", "one of: md, csv, json");
  if (o.paths < 2 || o.paths > 1000000000000LL)
    throw InputError("--paths", std::to_string(o.paths), "2 to 1e12 paths per probe and wavelength");
  if (o.orders < 0 || o.orders > 100000)
    throw InputError("--orders", std::to_string(o.orders), "0 (all orders) or 1 to 100000");
  if (!(o.sun_peak_share >= 0.0 && o.sun_peak_share <= 0.5))
    throw InputError("--sun-peak-share", format_shortest(o.sun_peak_share), "a share from 0 to 0.5");
  Checked c;
  // Only the camera position matters; a 1x1 image keeps the renderer's set-up (--compare) cheap.
  c.scene = load_scene(o.scene, [](SceneLoader& l) {
    l.apply_override("camera.width", "1", "reference");
    l.apply_override("camera.height", "1", "reference");
  });
  for (const auto& p : o.probes) c.probes.push_back(parse_reference_probe(p, "--probe"));
  if (c.probes.empty()) c.probes = standard_reference_probes(c.scene);
  if (o.compare && o.orders > 1)
    throw InputError("--orders", std::to_string(o.orders),
                     "0 or 1 with --compare (the renderer computes single scattering or all the orders it is set to)");
  c.settings.paths = o.paths;
  {
    // A whole number that fits in 64 bits, as typed: not clamped, not wrapped.
    errno = 0;
    char* end = nullptr;
    const unsigned long long seed = std::strtoull(o.seed.c_str(), &end, 10);
    if (o.seed.empty() || o.seed.find_first_not_of("0123456789") != std::string::npos || *end || errno == ERANGE)
      throw InputError("--seed", o.seed, "a whole number from 0 to 18446744073709551615");
    c.settings.seed = seed;
  }
  c.settings.max_orders = o.orders;
  c.settings.sun_peak_share = o.sun_peak_share;
  c.settings.diffuse_irradiance = o.irradiance;
  c.settings.stokes = o.stokes;
  return c;
}

// What the renderer says at the same probes (its sky radiance and diffuse horizontal irradiance).
struct Deterministic {
  std::vector<Spectrum> radiance;
  SpectrumD diffuse;
  /// With --stokes: [probe][wavelength] the renderer's [I, Q, U, V] (with output.polarisation;
  /// SkyRenderer::stokes) in the reference's frame.
  std::vector<std::vector<std::array<double, 4>>> stokes;
};

Deterministic render_probes(Scene scene, const Checked& c, int orders) {
  if (orders == 1) scene.render.scattering_orders = 1;
  // With --stokes the renderer's polarisation is compared: its vector tables.
  if (c.settings.stokes && (scene.render.scattering_orders < 2 || scene.render.ms_angular_degree >= 2))
    scene.output.polarisation = true;
  const SkyRenderer renderer(scene);
  Deterministic d;
  for (const auto& p : c.probes)
    d.radiance.push_back(renderer.radiance(direction_from_angles(p.azimuth_deg, p.elevation_deg)));
  if (c.settings.stokes)
    for (const auto& p : c.probes) {
      const Vec3 dir = direction_from_angles(p.azimuth_deg, p.elevation_deg);
      Spectrum i, q, u;
      renderer.stokes(dir, stokes_frame_axis(dir), i, q, u);
      std::vector<std::array<double, 4>> v(static_cast<size_t>(i.size()));
      for (Eigen::Index k = 0; k < i.size(); ++k) v[static_cast<size_t>(k)] = {i[k], q[k], u[k], 0.0};
      d.stokes.push_back(std::move(v));
    }
  if (c.settings.diffuse_irradiance) d.diffuse = irradiance_at_camera(renderer).diffuse_horizontal;
  return d;
}

// A user's probe label inside a CSV field (quotes doubled, RFC 4180) or a Markdown cell (| escaped).
std::string csv_quoted(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}
std::string markdown_cell(const std::string& s) {
  std::string out;
  for (char ch : s) out += ch == '|' ? std::string("\\|") : std::string(1, ch);
  return out;
}

std::string format_table(const ReferenceResult& r, const Deterministic* det, const std::string& format,
                         const Scene& scene) {
  std::ostringstream t;
  const size_t n = r.wavelengths_nm.size();
  // Relative figures only where the reference has light (no sky in the planet's shadow gives 0 / 0):
  // empty cells then, never a NaN.
  const bool md = format == "md";
  auto num = [](const char* fmt, double v) {
    char b[64];
    std::snprintf(b, sizeof b, fmt, v);
    return std::string(b);
  };
  const bool stokes = !r.stokes.empty();
  // The Stokes vector's derived figures: degree and angle (deg, from the vertical towards the
  // observer's left) of linear polarisation; empty where there is no light.
  auto polarisation_cells = [&](const std::array<double, 4>& v, const std::array<double, 4>& e) {
    std::vector<std::string> cells;
    const bool lit = v[0] > 0.0;
    if (md) {
      cells = {num("%.6g", v[0]), lit ? num("%.4f", std::hypot(v[1], v[2]) / v[0]) : "",
               lit ? num("%.2f", 0.5 * std::atan2(v[2], v[1]) * 180.0 / kPi) : "", lit ? num("%.2g", v[3] / v[0]) : ""};
    } else {
      for (size_t c = 0; c < 4; ++c) cells.push_back(num("%.9g", v[c]));
      for (size_t c = 0; c < 4; ++c) cells.push_back(num("%.9g", e[c]));
      cells.push_back(lit ? num("%.6g", std::hypot(v[1], v[2]) / v[0]) : "");
      cells.push_back(lit ? num("%.6g", 0.5 * std::atan2(v[2], v[1]) * 180.0 / kPi) : "");
    }
    return cells;
  };
  const bool det_stokes = det && !det->stokes.empty();
  const size_t stokes_columns = (md ? 4 : 10) + (det_stokes ? (md ? 3 : 5) : 0);
  auto row = [&](const std::string& label, double az, double el, size_t i, double mc, double se, double renderer,
                 const std::array<double, 4>* sv, const std::array<double, 4>* sv_error,
                 const std::array<double, 4>* renderer_sv) {
    const bool relative = mc > 0.0 && se > 0.0;
    std::vector<std::string> cells = {md ? markdown_cell(label) : csv_quoted(label),
                                      num(md ? "%.2f" : "%.6g", az),
                                      num(md ? "%.2f" : "%.6g", el),
                                      num("%g", r.wavelengths_nm[i]),
                                      num(md ? "%.6g" : "%.9g", mc),
                                      md ? (relative ? num("%.3f", 100.0 * se / mc) : "") : num("%.9g", se)};
    if (det) {
      cells.push_back(num(md ? "%.6g" : "%.9g", renderer));
      cells.push_back(relative ? num(md ? "%+.2f" : "%.6g", 100.0 * (renderer / mc - 1.0)) : "");
      cells.push_back(relative ? num(md ? "%+.1f" : "%.6g", (renderer - mc) / se) : "");
    }
    if (stokes) {
      auto extra = sv ? polarisation_cells(*sv, *sv_error) : std::vector<std::string>(stokes_columns);
      if (sv && det_stokes) {
        // The renderer's intensity (vector transport) against the vector reference's I.
        const auto& v = *renderer_sv;
        const double vi = (*sv)[0], ve = (*sv_error)[0];
        const bool vector_relative = vi > 0.0 && ve > 0.0;
        const std::string dolp = v[0] > 0.0 ? num(md ? "%.4f" : "%.6g", std::hypot(v[1], v[2]) / v[0]) : "";
        extra.push_back(vector_relative ? num(md ? "%+.2f" : "%.6g", 100.0 * (v[0] / vi - 1.0)) : "");
        extra.push_back(vector_relative ? num(md ? "%+.1f" : "%.6g", (v[0] - vi) / ve) : "");
        if (!md) {
          extra.push_back(num("%.9g", v[1]));
          extra.push_back(num("%.9g", v[2]));
        }
        extra.push_back(dolp);
      }
      cells.insert(cells.end(), extra.begin(), extra.end());
    }
    for (size_t c = 0; c < cells.size(); ++c) t << (md ? (c ? " | " : "| ") : (c ? "," : "")) << cells[c];
    t << (md ? " |\n" : "\n");
  };
  if (format == "md") {
    t << "| probe | azimuth (deg) | elevation (deg) | wavelength (nm) | Monte Carlo | standard error (%) |"
      << (det ? " renderer | renderer - MC (%) | (renderer - MC) / sigma |" : "")
      << (stokes ? " I (polarised) | DoLP | AoLP (deg) | V / I |" : "")
      << (det_stokes ? " renderer - I (%) | (renderer - I) / sigma | renderer DoLP |" : "") << "\n"
      << "| --- | ---: | ---: | ---: | ---: | ---: |" << (det ? " ---: | ---: | ---: |" : "")
      << (stokes ? " ---: | ---: | ---: | ---: |" : "") << (det_stokes ? " ---: | ---: | ---: |" : "") << "\n";
  } else {
    t << "probe,azimuth_deg,elevation_deg,wavelength_nm,monte_carlo,standard_error"
      << (det ? ",renderer,renderer_minus_mc_percent,renderer_minus_mc_sigma" : "")
      << (stokes ? ",stokes_i,stokes_q,stokes_u,stokes_v,stokes_i_error,stokes_q_error,stokes_u_error,stokes_v_error,"
                   "degree_of_linear_polarisation,angle_of_linear_polarisation_deg"
                 : "")
      << (det_stokes
              ? ",renderer_minus_stokes_i_percent,renderer_minus_stokes_i_sigma,renderer_stokes_q,renderer_stokes_u,"
                "renderer_degree_of_linear_polarisation"
              : "")
      << "\n";
  }
  for (size_t k = 0; k < r.probes.size(); ++k)
    for (size_t i = 0; i < n; ++i)
      row(r.probes[k].label, r.probes[k].azimuth_deg, r.probes[k].elevation_deg, i, r.radiance[k][i],
          r.radiance_standard_error[k][i], det ? static_cast<double>(det->radiance[k][static_cast<long>(i)]) : 0.0,
          stokes ? &r.stokes[k][i] : nullptr, stokes ? &r.stokes_standard_error[k][i] : nullptr,
          det_stokes ? &det->stokes[k][i] : nullptr);
  for (size_t i = 0; i < r.diffuse_horizontal.size(); ++i)
    row("diffuse horizontal irradiance", 0.0, 90.0, i, r.diffuse_horizontal[i], r.diffuse_horizontal_standard_error[i],
        det ? det->diffuse[static_cast<long>(i)] : 0.0, nullptr, nullptr, nullptr);
  if (format == "md") {
    t << "\nRadiance in W m^-2 sr^-1 nm^-1 (irradiance in W m^-2 nm^-1), sun at elevation " << scene.sun.elevation_deg
      << " deg, azimuth " << scene.sun.azimuth_deg << " deg; " << r.settings.paths << " paths per value, seed "
      << r.settings.seed << ", "
      << (r.settings.max_orders == 0 ? std::string("all orders") : std::to_string(r.settings.max_orders) + " order(s)")
      << (r.settings.sun_peak_share > 0.0
              ? ", a share " + format_shortest(r.settings.sun_peak_share) + " of scatterings drawn about the sun"
              : std::string())
      << "; " << r.seconds << " s.\n";
    if (stokes)
      t << "Polarisation (vector transport, the same number of paths): I with polarisation's coupling into "
           "intensity (the Monte Carlo column is scalar); degree and angle of linear polarisation, the angle from "
           "the vertical towards the observer's left (at the zenith from north); aerosols neither polarise nor "
           "depolarise in this model."
        << (det_stokes ? " The renderer runs with output.polarisation = true (vector transport for the air; aerosols "
                         "carry the polarisation of light scattered more than once as far as its quadrupole; with the "
                         "isotropic tables of --quality draft only its single scattering is polarised): its intensity "
                         "is compared with I as well as with the scalar Monte Carlo."
                       : "")
        << "\n";
  }
  return t.str();
}

std::string format_json(const ReferenceResult& r, const Deterministic* det, const Scene& scene) {
  nlohmann::json j;
  j["skyspec_version"] = version_string();
  j["paths"] = r.settings.paths;
  j["seed"] = r.settings.seed;
  j["max_orders"] = r.settings.max_orders;
  j["sun_peak_share"] = r.settings.sun_peak_share;
  j["seconds"] = r.seconds;
  j["wavelengths_nm"] = r.wavelengths_nm;
  j["sun_elevation_deg"] = scene.sun.elevation_deg;
  j["sun_azimuth_deg"] = scene.sun.azimuth_deg;
  j["scene"] = scene_to_toml(scene, SceneTomlKeys::Recorded);
  j["probes"] = nlohmann::json::array();
  for (size_t k = 0; k < r.probes.size(); ++k) {
    nlohmann::json p{{"label", r.probes[k].label},
                     {"azimuth_deg", r.probes[k].azimuth_deg},
                     {"elevation_deg", r.probes[k].elevation_deg},
                     {"radiance", r.radiance[k]},
                     {"standard_error", r.radiance_standard_error[k]}};
    if (det)
      p["renderer"] = std::vector<double>(det->radiance[k].data(), det->radiance[k].data() + det->radiance[k].size());
    if (!r.stokes.empty()) {
      p["stokes"] = r.stokes[k];
      p["stokes_standard_error"] = r.stokes_standard_error[k];
    }
    if (det && !det->stokes.empty()) p["renderer_stokes"] = det->stokes[k];
    j["probes"].push_back(p);
  }
  if (!r.diffuse_horizontal.empty()) {
    j["diffuse_horizontal"] = {{"irradiance", r.diffuse_horizontal},
                               {"standard_error", r.diffuse_horizontal_standard_error}};
    if (det)
      j["diffuse_horizontal"]["renderer"] =
          std::vector<double>(det->diffuse.data(), det->diffuse.data() + det->diffuse.size());
  }
  return j.dump(1) + "\n";
}

int run(const ReferenceOptions& o) {
  const Checked c = check(o);
  if (!o.out.empty()) {  // before minutes of paths, not after (not in check(): it may create the folder)
    const std::filesystem::path out(o.out);
    ensure_writable_directory(out.has_parent_path() ? out.parent_path() : std::filesystem::path("."), "--out");
  }
  // A time budget, as renders have: a pilot of 256 paths at the first probe (every wavelength, the
  // same settings), extrapolated to every probe and the irradiance; above 24 hours refused unless
  // --force (--paths 1e12 ran for years without a word).
  if (!o.force) {
    ReferenceSettings pilot = c.settings;
    pilot.paths = std::min<long long>(o.paths, 256);
    pilot.diffuse_irradiance = false;
    const auto t0 = std::chrono::steady_clock::now();
    monte_carlo_reference(c.scene, {c.probes.front()}, pilot, {});
    const double per_path =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / static_cast<double>(pilot.paths);
    const double seconds =
        per_path * static_cast<double>(o.paths) * static_cast<double>(c.probes.size() + (o.irradiance ? 1 : 0));
    if (seconds > 86400.0)
      throw InputError::refused("--force", "the Monte Carlo reference would take about " + format_duration(seconds) +
                                               " at these settings (" + std::to_string(o.paths) + " paths x " +
                                               std::to_string(c.probes.size()) + " probe(s), measured on " +
                                               std::to_string(pilot.paths) + "); use fewer --paths, or --force");
  }
  ReferenceResult result;
  {
    ProgressBar bar("monte carlo", o.quiet);
    result =
        monte_carlo_reference(c.scene, c.probes, c.settings, [&bar](int done, int total) { bar.update(done, total); });
    bar.finish();
  }
  std::unique_ptr<Deterministic> det;
  if (o.compare) det = std::make_unique<Deterministic>(render_probes(c.scene, c, o.orders));
  const std::string text =
      o.format == "json" ? format_json(result, det.get(), c.scene) : format_table(result, det.get(), o.format, c.scene);
  print_or_write(text, o.out);
  return kExitOk;
}

}  // namespace

Command add_reference_command(CLI::App& app) {
  auto o = std::make_shared<ReferenceOptions>();
  auto* cmd = app.add_subcommand(
      "reference", "Monte Carlo reference radiance (all scattering orders, with standard errors) in sky directions");
  cmd->footer(
      "Examples:\n"
      "  skyspec reference --sun-elevation 10 --compare\n"
      "  skyspec reference --probe zenith=0,90 --probe 180,1 --paths 1000000 --format json\n"
      "Backward path tracing in the scene's spherical shell (src/transport/monte_carlo.hpp), written\n"
      "independently of the renderer: no tables, every order, the scene's Rayleigh (with the King\n"
      "factor's depolarisation), aerosol phase function, ozone and Lambertian ground. One estimate per\n"
      "probe and wavelength, each depending only on the seed, --paths, the direction and the wavelength.\n"
      "Without --probe: the zenith, 45 deg up towards the sun, and 1 deg above the horizon towards,\n"
      "across and away from it. --compare adds the renderer's radiance (and irradiance) and their\n"
      "difference in percent and in standard errors (docs/validation.md). --stokes adds each probe's\n"
      "Stokes vector in the frame of the vertical through the line of sight (Q > 0: polarised in that\n"
      "plane; U > 0: at 45 deg from it towards the observer's left); with --compare, beside the\n"
      "renderer's, rendered with output.polarisation (docs/polarisation.md).");
  o->scene.flags = spectrum_flags();
  append_flags(o->scene.flags, sun_flags());
  o->scene.flags.push_back({"--position", "camera.position_m", "observer east,north,height in m", {}, true});
  add_scene_options(*cmd, o->scene);
  add_quality_option(*cmd, o->scene);
  cmd->add_option("--probe", o->probes, "a direction: azimuth,elevation or label=azimuth,elevation (deg); repeatable");
  cmd->add_option("--paths", o->paths, "paths per probe and wavelength")->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed")->capture_default_str();
  cmd->add_option("--orders", o->orders,
                  "0: all scattering orders; k: up to k scattering or ground events (1: single scattering)")
      ->capture_default_str();
  cmd->add_option("--sun-peak-share", o->sun_peak_share,
                  "the share of scatterings whose direction is drawn about the sun instead of the path (0 to 0.5; "
                  "unbiased either way): far smaller errors in fog and other forward-peaked media, which score "
                  "rarely and hugely without it")
      ->capture_default_str();
  cmd->add_flag("--irradiance", o->irradiance, "also the diffuse horizontal irradiance at the observer");
  cmd->add_flag("--compare", o->compare, "also the renderer's values at the same probes, and the differences");
  cmd->add_flag("--stokes", o->stokes,
                "also the Stokes vector [I, Q, U, V] of each probe, with the degree and angle of linear polarisation "
                "(vector transport: as many paths again)");
  cmd->add_option("--format", o->format, "md (Markdown table), csv or json")->capture_default_str();
  cmd->add_option("--out", o->out, "write to this file instead of standard output");
  cmd->add_flag("-q,--quiet", o->quiet, "no progress bar");
  cmd->add_flag("--force", o->force, "run even if the estimated time exceeds 24 hours");
  return {cmd, [o] { return run(*o); }, [o] { check(*o); }};
}

}  // namespace skyspec::cli
