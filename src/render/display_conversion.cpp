// `skyspec convert`: an existing EXR through the display pipeline.
#include "render/display_conversion.hpp"

#include <cmath>
#include <cstdlib>
#include <map>

#include "base/atomic_file.hpp"
#include "base/output_lock.hpp"
#include "base/text_format.hpp"
#include "io/png_image.hpp"
#include "io/provenance.hpp"
#include "io/rgb_exr.hpp"
#include "skyspec/error.hpp"
#include "skyspec/version.hpp"

namespace skyspec {
namespace {

bool is_rec709(const Chromaticities& c) {
  const Chromaticities r = rec709_chromaticities();
  const auto near = [](const double a[2], const double b[2]) {
    return std::abs(a[0] - b[0]) < 1e-4 && std::abs(a[1] - b[1]) < 1e-4;
  };
  return near(c.red, r.red) && near(c.green, r.green) && near(c.blue, r.blue) && near(c.white, r.white);
}

}  // namespace

ConversionOutputs convert_exr_for_display(const std::filesystem::path& input, const std::filesystem::path& directory,
                                          const std::string& name, const DisplaySettings& settings,
                                          std::optional<double> manual_ev, bool png) {
  if (!png && settings.exr_space.empty())
    throw InputError(conversion_setting::kPng, "off",
                     std::string("at least one output: the PNG or ") + display_setting::kExrSpace);
  if (name.empty() || name.find('/') != std::string::npos)
    throw InputError(conversion_setting::kName, "\"" + name + "\"", "a file name without '/'");
  ensure_writable_directory(directory, conversion_setting::kDirectory);
  const DisplayPipeline pipeline(settings);  // checks the names before reading anything
  if (!std::filesystem::is_regular_file(input))
    throw InputError(conversion_setting::kInput, "'" + input.string() + "'", "an existing EXR file");
  const OutputLock lock(directory, name, conversion_setting::kOutputs);  // one writer per name
  if (png)
    refuse_output_replacing_input(directory / (name + ".png"), conversion_setting::kOutputs,
                                  {{conversion_setting::kInput, input}});
  if (!settings.exr_space.empty())
    refuse_output_replacing_input(
        directory / (name + "-" + find_working_space(settings.exr_space).file_suffix + ".exr"),
        conversion_setting::kOutputs, {{conversion_setting::kInput, input}});
  const RgbExrImage image = read_rgb_exr(input);
  if (image.has_chromaticities && !is_rec709(image.chromaticities))
    throw InputError("input EXR", "'" + input.string() + "'",
                     "R, G, B in linear Rec.709 (skyspec's EXRs; its chromaticities attribute says other primaries)");
  for (float v : image.rgb)
    if (!std::isfinite(v)) throw IoError("EXR '" + input.string() + "': non-finite R, G, B values");

  ConversionOutputs out;
  ExposureSettings exposure = settings.exposure;
  if (manual_ev) {
    exposure.mode = ExposureSettings::Mode::Manual;
    exposure.ev = *manual_ev;
  }
  // The recorded scale: a double attribute, or text in files written before it was one.
  std::optional<double> recorded;
  std::string recorded_text;
  if (const auto d = image.doubles.find(kExposureScaleAttribute); d != image.doubles.end()) {
    recorded = d->second;
    recorded_text = format_number(d->second);
  } else if (const auto t = image.strings.find(kExposureScaleAttribute); t != image.strings.end()) {
    recorded = std::strtod(t->second.c_str(), nullptr);
    recorded_text = t->second;
  }
  if (exposure.mode == ExposureSettings::Mode::Automatic && recorded) {
    // Untrusted: the same range as a manual exposure (EV -200 to 200), so that a crafted 1e308 or
    // 5e-324 cannot make an all-black or all-white picture without a word.
    const double scale = *recorded;
    if (!(scale >= std::exp2(-200.0) && scale <= std::exp2(200.0)))
      throw IoError("EXR '" + input.string() + "': skyspec:exposureScale \"" + recorded_text +
                    "\" is not an exposure scale from 2^-200 to 2^200 (EV -200 to 200); give --exposure to choose one");
    out.exposure = resolve_exposure(exposure, scale);
    // What is applied is the number, whatever the file's text says.
    out.exposure.description =
        "recorded in the file: scale = " + format_number(scale) + " (EV " + format_number(std::log2(scale)) + ")";
  } else {
    out.exposure = resolve_exposure(exposure, exposure.mode == ExposureSettings::Mode::Automatic
                                                  ? metered_exposure_scale(image.rgb, image.width, image.height)
                                                  : 1.0);
  }
  out.display = pipeline.describe();

  std::map<std::string, std::string> provenance;
  for (const auto& [key, value] : image.strings)
    if (key.rfind("skyspec:", 0) == 0) provenance[key] = value;
  provenance["skyspec:convertedFrom"] = input.string();
  provenance["skyspec:exposure"] = out.exposure.description;
  provenance.erase(kExposureScaleAttribute);  // a number: written as a double attribute below

  try {
    if (png) {
      out.png = directory / (name + ".png");
      std::vector<std::pair<std::string, std::string>> text = {{"Software", std::string("skyspec ") + version_string()},
                                                               {"skyspec:display", out.display},
                                                               {"skyspec:exposure", out.exposure.description},
                                                               {"skyspec:convertedFrom", input.string()}};
      for (const char* key : {kVersionAttribute, kSceneAttribute, kDataAttribute})  // the render's provenance
        if (const auto it = provenance.find(key); it != provenance.end()) text.emplace_back(key, it->second);
      write_png_display(out.png, image.width, image.height, pipeline.encode(image.rgb, out.exposure.scale),
                        settings.png_bit_depth, pipeline.png_tag(), text);
    }
    if (!settings.exr_space.empty()) {
      const WorkingSpace& space = find_working_space(settings.exr_space);
      out.working_exr = directory / (name + "-" + space.file_suffix + ".exr");
      provenance["skyspec:workingSpace"] =
          space.name + " (scene-linear, converted by " + pipeline.config().describe() + ")";
      const auto path = image.strings.find("skyspec:renderPath");
      provenance["skyspec:units"] =
          working_space_units(space, path != image.strings.end() && path->second == "rgb-fast");
      write_rgb_exr(out.working_exr, image.width, image.height, to_working_space(pipeline.config(), image.rgb, space),
                    space.chromaticities, provenance, {}, {{kExposureScaleAttribute, out.exposure.scale}},
                    image.latlong_envmap);
    }
  } catch (...) {
    std::error_code ec;
    if (!out.png.empty()) std::filesystem::remove(out.png, ec);
    throw;
  }
  return out;
}

}  // namespace skyspec
