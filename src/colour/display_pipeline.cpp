// The OpenColorIO display pipeline (OpenColorIO 2.1 C++ API).
#include "colour/display_pipeline.hpp"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <system_error>

#include "base/embedded_data.hpp"
#include "colour/tone_mapping.hpp"
#include "skyspec/error.hpp"

namespace OCIO = OCIO_NAMESPACE;

namespace skyspec {

// ---------------------------------------------------------------------------------------------
// The config
// ---------------------------------------------------------------------------------------------

namespace {

constexpr const char* kBuiltinConfig = "ocio/config.ocio";
constexpr const char* kXyzSpace = "CIE-XYZ-D65";
constexpr const char* kAcesInterchangeRole = "aces_interchange";
constexpr const char* kAp0ToXyzD65 = "UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD";

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string text;
  for (size_t i = 0; i < names.size(); ++i) text += (i ? ", \"" : "\"") + names[i] + "\"";
  return text.empty() ? "(none)" : text;
}

/// The entry of `names` equal to `wanted`, or else its only case-insensitive match; empty if none.
std::string match_name(const std::vector<std::string>& names, const std::string& wanted) {
  for (const auto& n : names)
    if (n == wanted) return n;
  std::string found;
  for (const auto& n : names)
    if (lower(n) == lower(wanted)) {
      if (!found.empty()) return {};
      found = n;
    }
  return found;
}

}  // namespace

struct OcioConfig::Impl {
  OCIO::ConstConfigRcPtr config;
  OcioConfigSource source;
  std::string input_space;  // scene-referred space skyspec's XYZ goes into
  bool via_aces = false;    // true: XYZ -> ACES2065-1 with the built-in Bradford first
};

namespace {

// A config read and checked (OcioConfig's constructor).
std::shared_ptr<const OcioConfig::Impl> load_config(const OcioConfigSource& source) {
  auto impl = std::make_shared<OcioConfig::Impl>();
  impl->source = source;
  const std::string setting = source.origin.empty() ? "OCIO config" : source.origin;
  // Only regular files go to OpenColorIO: given a folder, its YAML reader (yaml-cpp 0.7) leaks a
  // buffer (LeakSanitizer; tests/fuzz/regressions/cli/), and the message is clearer.
  std::error_code ec;
  if (!source.path.empty() && !std::filesystem::is_regular_file(source.path, ec))
    throw InputError(setting, "'" + source.path + "'",
                     std::string("a readable, valid OpenColorIO 2.1 config file (") +
                         (std::filesystem::exists(source.path, ec) ? "this is not a regular file" : "no such file") +
                         ")");
  try {
    if (source.path.empty()) {
      std::istringstream text{std::string(embedded_file(kBuiltinConfig))};
      impl->config = OCIO::Config::CreateFromStream(text);
    } else {
      impl->config = OCIO::Config::CreateFromFile(source.path.c_str());
    }
    impl->config->validate();
  } catch (const OCIO::Exception& e) {
    if (source.path.empty()) throw Error(std::string("internal error: the built-in OCIO config: ") + e.what());
    throw InputError(setting, "'" + source.path + "'",
                     "a readable, valid OpenColorIO 2.1 config file (OpenColorIO says: " + std::string(e.what()) + ")");
  }
  const auto xyz = impl->config->getColorSpace(kXyzSpace);
  if (xyz && xyz->getReferenceSpaceType() == OCIO::REFERENCE_SPACE_SCENE) {
    impl->input_space = xyz->getName();
  } else if (const auto aces = impl->config->getColorSpace(kAcesInterchangeRole)) {
    impl->input_space = aces->getName();
    impl->via_aces = true;
  } else {
    throw InputError(setting, "'" + source.path + "'",
                     "a config with a scene-referred colour space \"CIE-XYZ-D65\" or the role aces_interchange "
                     "(skyspec's images enter the config there)");
  }
  return impl;
}

}  // namespace

OcioConfig::OcioConfig(const OcioConfigSource& source) {
  if (source.path.empty()) {
    // The built-in config is read once per process (the viewer asks for it with every frame); a
    // config is immutable and OpenColorIO's const configs may be shared between threads.
    static const std::shared_ptr<const Impl> builtin = load_config(OcioConfigSource{});
    impl_ = builtin;
    return;
  }
  impl_ = load_config(source);
}

OcioConfig::~OcioConfig() = default;

bool OcioConfig::is_builtin() const { return impl_->source.path.empty(); }

std::string OcioConfig::describe() const {
  if (is_builtin()) return "skyspec built-in config (data/ocio/config.ocio)";
  return "'" + impl_->source.path + "'" + (impl_->source.origin.empty() ? "" : " (from " + impl_->source.origin + ")");
}

std::vector<std::string> OcioConfig::displays() const {
  std::vector<std::string> names;
  for (int i = 0; i < impl_->config->getNumDisplays(); ++i) names.emplace_back(impl_->config->getDisplay(i));
  return names;
}

std::string OcioConfig::default_display() const { return impl_->config->getDefaultDisplay(); }

std::vector<std::string> OcioConfig::views(const std::string& display) const {
  std::vector<std::string> names;
  for (int i = 0; i < impl_->config->getNumViews(display.c_str()); ++i)
    names.emplace_back(impl_->config->getView(display.c_str(), i));
  return names;
}

std::string OcioConfig::default_view(const std::string& display) const {
  return impl_->config->getDefaultView(display.c_str());
}

std::vector<std::string> OcioConfig::looks() const {
  std::vector<std::string> names;
  for (int i = 0; i < impl_->config->getNumLooks(); ++i) names.emplace_back(impl_->config->getLookNameByIndex(i));
  return names;
}

std::vector<std::string> OcioConfig::colour_spaces() const {
  std::vector<std::string> names;
  for (int i = 0; i < impl_->config->getNumColorSpaces(); ++i)
    names.emplace_back(impl_->config->getColorSpaceNameByIndex(i));
  return names;
}

std::string OcioConfig::input_description() const {
  if (!impl_->via_aces) return "\"" + impl_->input_space + "\" (scene-referred XYZ)";
  return "\"" + impl_->input_space + "\" (role aces_interchange), reached with the built-in \"" +
         std::string(kAp0ToXyzD65) + "\" inverted";
}

namespace {

/// skyspec's linear Rec.709 -> the config's input space: the engine's Rec.709 -> XYZ matrix (so
/// that the pipeline sees exactly the XYZ the engine computed), then for configs without an XYZ
/// space the built-in XYZ (D65) -> ACES2065-1.
OCIO::GroupTransformRcPtr input_transform(const OcioConfig::Impl& c) {
  auto group = OCIO::GroupTransform::Create();
  const Eigen::Matrix3d m = linear_rec709_to_xyz();
  double m44[16] = {m(0, 0), m(0, 1), m(0, 2), 0, m(1, 0), m(1, 1), m(1, 2), 0,
                    m(2, 0), m(2, 1), m(2, 2), 0, 0,       0,       0,       1};
  auto matrix = OCIO::MatrixTransform::Create();
  matrix->setMatrix(m44);
  group->appendTransform(matrix);
  if (c.via_aces) {
    auto to_aces = OCIO::BuiltinTransform::Create();
    to_aces->setStyle(kAp0ToXyzD65);
    to_aces->setDirection(OCIO::TRANSFORM_DIR_INVERSE);
    group->appendTransform(to_aces);
  }
  return group;
}

OCIO::ConstCPUProcessorRcPtr cpu_processor(const OCIO::ConstConfigRcPtr& config, const OCIO::ConstTransformRcPtr& t) {
  return config->getProcessor(t)->getOptimizedCPUProcessor(OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32,
                                                           OCIO::OPTIMIZATION_DEFAULT);
}

void apply_in_place(const OCIO::ConstCPUProcessorRcPtr& cpu, std::vector<float>& rgb) {
  const long pixels = static_cast<long>(rgb.size() / 3);
  if (pixels == 0) return;
  OCIO::PackedImageDesc desc(rgb.data(), pixels, 1, 3);
  cpu->apply(desc);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The pipeline
// ---------------------------------------------------------------------------------------------

struct DisplayPipeline::Impl {
  DisplaySettings settings;
  OcioConfig config;
  std::string display, view, look;
  bool ocio_look = false;
  std::optional<ToneOperator> tone;
  OCIO::ConstCPUProcessorRcPtr processor;

  explicit Impl(const DisplaySettings& s) : settings(s), config(s.config) {}
};

DisplayPipeline::DisplayPipeline(const DisplaySettings& s) : impl_(std::make_unique<Impl>(s)) {
  Impl& p = *impl_;
  const OcioConfig& c = p.config;
  const std::string in_config = " of " + c.describe();

  p.display = s.display.empty() ? c.default_display() : match_name(c.displays(), s.display);
  if (p.display.empty())
    throw InputError(display_setting::kDisplay, "\"" + s.display + "\"",
                     "one of the displays" + in_config + ": " + quoted_list(c.displays()));
  p.view = s.view.empty() ? c.default_view(p.display) : match_name(c.views(p.display), s.view);
  if (p.view.empty())
    throw InputError(display_setting::kView, "\"" + s.view + "\"",
                     "one of the views of display \"" + p.display + "\": " + quoted_list(c.views(p.display)));
  if (!s.look.empty()) {
    p.look = match_name(c.looks(), s.look);
    if (!p.look.empty()) {
      p.ocio_look = true;
    } else if (const auto op = tone_operator_from_name(lower(s.look))) {
      p.look = to_string(*op);
      p.tone = op;
    } else {
      throw InputError(display_setting::kLook, "\"" + s.look + "\"",
                       "an OCIO look" + in_config + " (" + quoted_list(c.looks()) + ") or a skyspec look (" +
                           quoted_list(tone_operator_names()) + ")");
    }
  }
  if (s.look_white && !(p.tone == ToneOperator::ReinhardExtended || p.tone == ToneOperator::ReinhardLuminance))
    throw InputError(display_setting::kLookWhite, std::to_string(*s.look_white),
                     std::string("only with ") + display_setting::kLook + " reinhard-extended or reinhard-luminance");
  if (s.png_bit_depth != 8 && s.png_bit_depth != 16)
    throw InputError(display_setting::kPngBits, std::to_string(s.png_bit_depth), "8 or 16");
  if (!s.exr_space.empty()) {
    const WorkingSpace& ws = find_working_space(s.exr_space);
    if (!c.impl().config->getColorSpace(ws.name.c_str()))
      throw InputError(display_setting::kExrSpace, "\"" + s.exr_space + "\"",
                       "a working space that " + c.describe() + " defines; it has " + quoted_list(c.colour_spaces()));
  }

  const auto& ci = c.impl();
  auto group = input_transform(ci);
  if (p.ocio_look) {
    auto look = OCIO::LookTransform::Create();
    look->setSrc(ci.input_space.c_str());
    look->setDst(ci.input_space.c_str());
    look->setLooks(p.look.c_str());
    group->appendTransform(look);
  }
  auto display_view = OCIO::DisplayViewTransform::Create();
  display_view->setSrc(ci.input_space.c_str());
  display_view->setDisplay(p.display.c_str());
  display_view->setView(p.view.c_str());
  group->appendTransform(display_view);
  try {
    p.processor = cpu_processor(ci.config, group);
  } catch (const OCIO::Exception& e) {
    throw InputError(
        std::string(display_setting::kDisplay) + " / " + display_setting::kView + " / " + display_setting::kLook,
        "\"" + p.display + "\" / \"" + p.view + "\" / \"" + p.look + "\"",
        "a combination that " + c.describe() + " can build (OpenColorIO says: " + e.what() + ")");
  }
}

DisplayPipeline::~DisplayPipeline() = default;
DisplayPipeline::DisplayPipeline(DisplayPipeline&&) noexcept = default;

const OcioConfig& DisplayPipeline::config() const { return impl_->config; }
const DisplaySettings& DisplayPipeline::settings() const { return impl_->settings; }
const std::string& DisplayPipeline::display() const { return impl_->display; }
const std::string& DisplayPipeline::view() const { return impl_->view; }
const std::string& DisplayPipeline::look() const { return impl_->look; }

std::string DisplayPipeline::look_kind() const {
  if (impl_->look.empty()) return "";
  return impl_->ocio_look ? "OCIO look" : "skyspec look (C++)";
}

std::string DisplayPipeline::describe() const {
  std::string text = "display \"" + impl_->display + "\", view \"" + impl_->view + "\"";
  text += impl_->look.empty() ? ", no look" : ", " + look_kind() + " \"" + impl_->look + "\"";
  return text + "; " + impl_->config.describe();
}

PngColourTag DisplayPipeline::png_tag() const {
  if (!impl_->config.is_builtin()) return PngColourTag::None;
  if (impl_->view == "Raw") return PngColourTag::None;
  if (impl_->display == "sRGB") return PngColourTag::Srgb;
  if (impl_->display == "Display P3") return PngColourTag::DisplayP3;
  if (impl_->display == "Rec.1886 Rec.709") return PngColourTag::Rec709;
  if (impl_->display == "Rec.2100-PQ") return PngColourTag::Rec2100Pq;
  return PngColourTag::None;
}

std::vector<float> DisplayPipeline::encode(std::vector<float> rgb, double exposure_scale) const {
  if (!std::isfinite(exposure_scale) || exposure_scale <= 0.0)
    throw Error("internal error: exposure scale must be positive and finite");
  const float scale = static_cast<float>(exposure_scale);
  for (float& v : rgb) v *= scale;
  if (impl_->tone) apply_tone_operator(*impl_->tone, rgb, impl_->settings.look_white);
  apply_in_place(impl_->processor, rgb);
  for (float& v : rgb) v = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
  return rgb;
}

// ---------------------------------------------------------------------------------------------
// Working spaces
// ---------------------------------------------------------------------------------------------

const std::vector<WorkingSpace>& working_spaces() {
  // ACES white: x = 0.32168, y = 0.33767 (SMPTE ST 2065-1). AP1: Academy S-2014-004.
  static const std::vector<WorkingSpace> spaces = {
      {"ACEScg", "acescg", Chromaticities{{0.713, 0.293}, {0.165, 0.830}, {0.128, 0.044}, {0.32168, 0.33767}}},
      {"ACES2065-1", "aces2065-1", Chromaticities{{0.7347, 0.2653}, {0.0, 1.0}, {0.0001, -0.0770}, {0.32168, 0.33767}}},
      {"Linear Rec.709", "linear-rec709", rec709_chromaticities()},
  };
  return spaces;
}

const WorkingSpace& find_working_space(const std::string& name, const std::string& setting) {
  std::vector<std::string> names;
  for (const auto& s : working_spaces()) names.push_back(s.name);
  const std::string found = match_name(names, name);
  for (const auto& s : working_spaces())
    if (s.name == found) return s;
  throw InputError(setting, "\"" + name + "\"", "one of " + quoted_list(names));
}

std::vector<float> to_working_space(const OcioConfig& config, const std::vector<float>& linear_rec709,
                                    const WorkingSpace& space) {
  const auto& ci = config.impl();
  if (!ci.config->getColorSpace(space.name.c_str()))
    throw InputError(
        display_setting::kExrSpace, "\"" + space.name + "\"",
        "a working space that " + config.describe() + " defines; it has " + quoted_list(config.colour_spaces()));
  auto group = input_transform(ci);
  auto convert = OCIO::ColorSpaceTransform::Create();
  convert->setSrc(ci.input_space.c_str());
  convert->setDst(space.name.c_str());
  group->appendTransform(convert);
  std::vector<float> rgb = linear_rec709;
  apply_in_place(cpu_processor(ci.config, group), rgb);
  return rgb;
}

std::string describe_displays_and_looks(const OcioConfig& config) {
  std::ostringstream out;
  out << "OpenColorIO " << OCIO::GetVersion() << ", " << config.describe() << "\n";
  out << "skyspec's images enter it as " << config.input_description() << "\n\n";
  out << "Displays (--display) and their views (--view); the first view is the default:\n";
  for (const auto& d : config.displays()) {
    out << "  " << d << (d == config.default_display() ? "  [default]" : "") << "\n";
    for (const auto& v : config.views(d)) out << "      " << v << "\n";
  }
  out << "\nLooks (--look):\n";
  for (const auto& l : config.looks()) out << "  " << l << "  (OCIO look of the config)\n";
  for (const auto& l : tone_operator_names())
    if (match_name(config.looks(), l).empty())
      out << "  " << l << "  (skyspec look, C++, before the OCIO display transform)\n";
  out << "\nScene-linear working spaces for --exr-space:\n";
  for (const auto& s : working_spaces()) out << "  " << s.name << "\n";
  return out.str();
}

std::string working_space_units(const WorkingSpace& space, bool rgb_fast) {
  return "R,G,B: scene-linear " + space.name + " (primaries and white in the chromaticities attribute)" +
         (rgb_fast ? ", converted from the RGB-fast path's 680, 550, 440 nm values in the sun's units"
                   : ", with Y = luminance in cd m^-2");
}

}  // namespace skyspec
