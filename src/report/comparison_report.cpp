// Reports and figures of `skyspec compare`.
#include "report/comparison_report.hpp"
#include "base/text_format.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "base/atomic_file.hpp"
#include "io/raster_image.hpp"
#include "report/svg_plot.hpp"
#include "skyspec/error.hpp"
#include "skyspec/version.hpp"

namespace skyspec {
namespace {

constexpr SkyRegion kRegions[4] = {SkyRegion::NearSun, SkyRegion::Horizon, SkyRegion::Zenith, SkyRegion::Rest};

std::string percent(double share) { return format_fixed(100.0 * share, 1) + " %"; }
std::string signed_percent_of_share(double v) { return (v >= 0 ? "+" : "") + format_fixed(100.0 * v, 1) + " %"; }

std::string table_row(const std::string& name, const RegionStats& s) {
  const auto& d = s.delta_e;
  if (d.pixels == 0) return "| " + name + " | 0 | | | | | | | | | |\n";
  return "| " + name + " | " + std::to_string(d.pixels) + " | " + format_fixed(d.mean, 2) + " | " +
         format_fixed(d.median, 2) + " | " + format_fixed(d.p95, 2) + " | " + format_fixed(d.max, 2) + " | " +
         percent(d.share_above_1) + " | " + percent(d.share_above_2) + " | " + percent(d.share_above_5) + " | " +
         signed_percent_of_share(s.luminance.mean) + " | " + format_fixed(100.0 * s.luminance.p95_abs, 1) + " % |\n";
}

const char* kTableHead =
    "| region | pixels | mean dE00 | median | p95 | max | > 1 | > 2 | > 5 | mean lum. error | p95 abs. lum. error |\n"
    "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";

nlohmann::json to_json(const RegionStats& s) {
  const auto& d = s.delta_e;
  const auto& l = s.luminance;
  return {{"pixels", d.pixels},
          {"delta_e_2000",
           {{"mean", d.mean},
            {"median", d.median},
            {"p95", d.p95},
            {"max", d.max},
            {"share_above_1", d.share_above_1},
            {"share_above_2", d.share_above_2},
            {"share_above_5", d.share_above_5}}},
          {"relative_luminance_error",
           {{"pixels", l.pixels},
            {"mean", l.mean},
            {"median_abs", l.median_abs},
            {"p95_abs", l.p95_abs},
            {"max_abs", l.max_abs}}}};
}

nlohmann::json regions_json(const std::array<RegionStats, 4>& regions) {
  nlohmann::json j = nlohmann::json::object();
  for (SkyRegion r : kRegions) j[region_key(r)] = to_json(regions[static_cast<size_t>(r)]);
  return j;
}

}  // namespace

std::string comparison_markdown(const ComparisonRun& run) {
  std::ostringstream out;
  const auto& c = run.comparison;
  out << "# RGB-fast vs spectral sky\n\n";
  out << "Made by skyspec " << version_string() << " with\n\n    " << run.command << "\n\n";
  out << "Scene: " << run.scene_summary << ". Reference: " << run.reference_label << ". Test: " << run.test_label
      << ".\n\n";
  out << "## Sun elevation " << format_fixed(run.sun_elevation_deg, 1) << " deg\n\n";
  out << "Delta E 2000 per pixel and relative luminance error (Y_RGB-fast - Y_spectral) / Y_spectral:\n\n";
  out << kTableHead << table_row("**all**", c.all);
  for (SkyRegion r : kRegions) out << table_row(to_string(r), c.regions[static_cast<size_t>(r)]);
  out << "\n";
  if (!run.delta_e_map_file.empty())
    out << "![Delta E 2000 map (0 to " << format_fixed(run.delta_e_max, 0) << ")](" << run.delta_e_map_file << ")\n";
  if (!run.side_by_side_file.empty())
    out << "![spectral (left) and RGB-fast (right) on the common white and exposure](" << run.side_by_side_file
        << ")\n";
  out << "\n";

  if (!run.sweep.empty()) {
    out << "## Sweep over sun elevation\n\n";
    out << "| sun elevation (deg) | mean dE00 | median | p95 | max | > 1 | > 2 | > 5 | mean near sun | mean horizon | "
           "mean zenith | mean rest | mean lum. error |\n";
    out << "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
    const SweepPoint* worst = &run.sweep.front();
    for (const auto& p : run.sweep) {
      const auto& d = p.all.delta_e;
      out << "| " << format_fixed(p.sun_elevation_deg, 1) << " | " << format_fixed(d.mean, 2) << " | "
          << format_fixed(d.median, 2) << " | " << format_fixed(d.p95, 2) << " | " << format_fixed(d.max, 2) << " | "
          << percent(d.share_above_1) << " | " << percent(d.share_above_2) << " | " << percent(d.share_above_5);
      for (SkyRegion r : kRegions) {
        const auto& rd = p.regions[static_cast<size_t>(r)].delta_e;
        out << " | " << (rd.pixels ? format_fixed(rd.mean, 2) : std::string("-"));
      }
      out << " | " << signed_percent_of_share(p.all.luminance.mean) << " |\n";
      if (d.mean > worst->all.delta_e.mean) worst = &p;
    }
    const auto& w = worst->all.delta_e;
    SkyRegion worst_region = SkyRegion::NearSun;
    for (SkyRegion r : kRegions)
      if (worst->regions[static_cast<size_t>(r)].delta_e.mean >
          worst->regions[static_cast<size_t>(worst_region)].delta_e.mean)
        worst_region = r;
    out << "\nWorst: sun at " << format_fixed(worst->sun_elevation_deg, 1) << " deg, mean Delta E 2000 "
        << format_fixed(w.mean, 2) << " (p95 " << format_fixed(w.p95, 2) << ", " << percent(w.share_above_2)
        << " of pixels above 2); there the worst region is " << to_string(worst_region) << " (mean "
        << format_fixed(worst->regions[static_cast<size_t>(worst_region)].delta_e.mean, 2) << ").\n\n";
    if (!run.sweep_plot_file.empty()) out << "![Delta E 2000 against sun elevation](" << run.sweep_plot_file << ")\n\n";
  }

  out << "## How the numbers are made\n\n" << comparison_rules(run.regions);
  out << "- Exposure factor of the reference image on sun-relative luminance: " << c.exposure_scale << ".\n";
  for (const auto& note : run.notes) out << "- " << note << "\n";
  out << "\nDelta E 2000 reading guide: about 1 is a just-noticeable difference side by side, 2 is visible to most "
         "observers, above 5 the colours are plainly different.\n";
  return out.str();
}

std::string comparison_json(const ComparisonRun& run) {
  nlohmann::json j;
  j["skyspec_version"] = version_string();
  j["command"] = run.command;
  j["scene"] = run.scene_summary;
  j["reference"] = run.reference_label;
  j["test"] = run.test_label;
  j["rules"] = {{"white", "extraterrestrial sun, Bradford-adapted to D65, unit luminance"},
                {"exposure", "automatic exposure of the reference image (log-average luminance -> 0.18)"},
                {"lab_white", "D65 at luminance 1 after exposure"},
                {"delta_e", "CIEDE2000, kL = kC = kH = 1"},
                {"percentiles", "linear interpolation between order statistics"},
                {"regions_deg",
                 {{"near_sun", run.regions.near_sun_deg},
                  {"horizon", run.regions.horizon_deg},
                  {"zenith", run.regions.zenith_deg}}}};
  j["notes"] = run.notes;
  j["result"] = {{"sun_elevation_deg", run.sun_elevation_deg},
                 {"exposure_scale", run.comparison.exposure_scale},
                 {"all", to_json(run.comparison.all)},
                 {"regions", regions_json(run.comparison.regions)}};
  nlohmann::json sweep = nlohmann::json::array();
  for (const auto& p : run.sweep)
    sweep.push_back(
        {{"sun_elevation_deg", p.sun_elevation_deg}, {"all", to_json(p.all)}, {"regions", regions_json(p.regions)}});
  j["sweep"] = sweep;
  j["files"] = {{"delta_e_map", run.delta_e_map_file},
                {"side_by_side", run.side_by_side_file},
                {"sweep_plot", run.sweep_plot_file}};
  return j.dump(2) + "\n";
}

std::string sweep_plot_svg(const std::vector<SweepPoint>& sweep) {
  std::vector<svg::Series> series;
  const auto add = [&](const std::string& name, const std::string& colour, bool dashed, auto value) {
    svg::Series s;
    s.name = name;
    s.colour = colour;
    s.dashed = dashed;
    for (const auto& p : sweep) {
      s.x.push_back(p.sun_elevation_deg);
      s.y.push_back(value(p));
    }
    series.push_back(s);
  };
  add("all pixels: mean", "#000000", false, [](const SweepPoint& p) { return p.all.delta_e.mean; });
  add("all pixels: 95th percentile", "#000000", true, [](const SweepPoint& p) { return p.all.delta_e.p95; });
  const char* colours[4] = {"#d62728", "#ff7f0e", "#1f77b4", "#2ca02c"};
  for (SkyRegion r : kRegions)
    add(to_string(r) + ": mean", colours[static_cast<size_t>(r)], false, [r](const SweepPoint& p) {
      const auto& d = p.regions[static_cast<size_t>(r)].delta_e;
      return d.pixels ? d.mean : std::nan("");
    });
  svg::Axes axes;
  axes.title = "RGB-fast vs spectral: Delta E 2000 against sun elevation";
  axes.x_label = "sun elevation (deg)";
  axes.y_label = "Delta E 2000";
  axes.width_px = 720;
  axes.height_px = 420;
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + svg::line_plot(axes, series) + "\n";
}

// ---------------------------------------------------------------------------------------------
// Pictures
// ---------------------------------------------------------------------------------------------

namespace {

int enlargement(int width, int height) {
  return std::max(1, (256 + std::max(width, height) - 1) / std::max(width, height));
}

std::vector<double> colour_bar_ticks(double max) {
  std::vector<double> ticks = {0};
  for (double base = 1; base <= max * (1 + 1e-9); base *= 10)
    for (double m : {1.0, 2.0, 5.0})
      if (base * m <= max * (1 + 1e-9)) ticks.push_back(base * m);
  if (std::abs(ticks.back() - max) > 1e-9 * max) ticks.push_back(max);
  return ticks;
}

std::string tick_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

void write_delta_e_map(const std::filesystem::path& path, const SkyComparison& c, double max) {
  if (!(max > 0.0) || !std::isfinite(max))
    throw InputError(kDeltaEMaxSetting, std::to_string(max), "a positive number");
  const int s = enlargement(c.width, c.height), W = c.width * s, H = c.height * s;
  const int font = W >= 384 ? 2 : 1, line = 9 * font, margin = 8;
  const int bar_w = 16, bar_x = margin + W + 12, label_x = bar_x + bar_w + 6;
  const int canvas_w = label_x + raster::Canvas::text_width(tick_text(max) + "+", font) + margin;
  const int top = margin + line + 4, canvas_h = top + H + 6 + line + margin;
  raster::Canvas canvas(
      std::max(canvas_w, margin + raster::Canvas::text_width("DELTA E 2000 (CIEDE2000)", font) + margin), canvas_h,
      {1, 1, 1});
  const raster::Rgb ink{0, 0, 0};
  canvas.text(margin, margin, "DELTA E 2000 (CIEDE2000)", ink, font);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(c.width) + static_cast<size_t>(x);
      for (int dy = 0; dy < s; ++dy)
        for (int dx = 0; dx < s; ++dx) {
          const int px = x * s + dx, py = y * s + dy;
          raster::Rgb colour;
          if (c.region[i] == kNotCompared) {
            const bool dark = ((px / 4) + (py / 4)) % 2 == 0;
            colour = dark ? raster::Rgb{0.55f, 0.55f, 0.55f} : raster::Rgb{0.7f, 0.7f, 0.7f};
          } else {
            colour = raster::cubehelix(c.delta_e[i] / max);
          }
          canvas.set(margin + px, top + py, colour);
        }
    }
  // Colour bar: value max at the top, 0 at the bottom, ticks with labels.
  for (int y = 0; y < H; ++y) canvas.fill_rect(bar_x, top + y, bar_w, 1, raster::cubehelix(1.0 - (y + 0.5) / H));
  for (double t : colour_bar_ticks(max)) {
    const int y = top + static_cast<int>(std::lround((1.0 - t / max) * (H - 1)));
    canvas.fill_rect(bar_x + bar_w, y, 4, 1, ink);
    const std::string label = tick_text(t) + (t == max ? "+" : "");
    canvas.text(label_x, std::clamp(y - 3 * font, top - 3 * font, top + H - 4 * font), label, ink, font);
  }
  canvas.text(margin, top + H + 6, "GREY CHECKS: NOT COMPARED", ink, font);
  canvas.write_png(path);
}

void write_side_by_side(const std::filesystem::path& path, const SkyComparison& c, const DisplayPipeline& pipeline,
                        const std::string& reference_label, const std::string& test_label) {
  const int s = enlargement(c.width, c.height), W = c.width * s, H = c.height * s;
  const int font = W >= 384 ? 2 : 1, line = 9 * font, margin = 8;
  raster::Canvas canvas(margin + W + margin + W + margin, margin + line + 4 + H + margin, {0.08f, 0.08f, 0.08f});
  const raster::Rgb ink{1, 1, 1};
  canvas.text(margin, margin, reference_label, ink, font);
  canvas.text(2 * margin + W, margin, test_label, ink, font);
  canvas.blit(pipeline.encode(c.reference_rgb, 1.0), c.width, c.height, margin, margin + line + 4, s);
  canvas.blit(pipeline.encode(c.test_rgb, 1.0), c.width, c.height, 2 * margin + W, margin + line + 4, s);
  canvas.write_png(path, pipeline.png_tag());
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
  AtomicOutputFile file(path);
  FILE* out = std::fopen(file.temporary_path().c_str(), "wb");
  if (!out) throw IoError("cannot open '" + file.temporary_path().string() + "': " + std::strerror(errno));
  const bool written = std::fwrite(text.data(), 1, text.size(), out) == text.size();
  const bool closed = std::fclose(out) == 0;
  if (!written || !closed) throw IoError("cannot write '" + path.string() + "'");
  file.commit();
}

}  // namespace skyspec
