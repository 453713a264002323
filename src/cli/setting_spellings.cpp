#include "setting_spellings.hpp"

#include "render/display_conversion.hpp"
#include "render/render_budget.hpp"
#include "report/comparison_report.hpp"
#include "skyspec/display.hpp"
#include "skyspec/scene.hpp"

namespace skyspec::cli {

const std::vector<std::pair<std::string, std::string>>& cli_spellings() {
  namespace d = display_setting;
  namespace c = conversion_setting;
  static const std::vector<std::pair<std::string, std::string>> table = {
      {d::kOcio, "--ocio"},
      {d::kDisplay, "--display"},
      {d::kView, "--view"},
      {d::kLook, "--look"},
      {d::kLookWhite, "--look-white"},
      {d::kExposureEv, "--exposure"},
      {d::kFNumber, "--f-number"},
      {d::kShutter, "--shutter"},
      {d::kIso, "--iso"},
      {d::kPngBits, "--png-bits"},
      {d::kExrSpace, "--exr-space"},
      {c::kInput, "INPUT"},
      {c::kDirectory, "--out"},
      {c::kName, "--name"},
      {c::kPng, "--no-png"},
      {kDeltaEMaxSetting, "--delta-e-max"},
      {kForceSetting, "--force"},
      {kSceneFileSetting, "--scene"},
  };
  return table;
}

}  // namespace skyspec::cli
