#include "setting_spellings.hpp"

#include "render/display_conversion.hpp"
#include "render/render_budget.hpp"
#include "report/comparison_report.hpp"
#include "skyspec/display.hpp"
#include "skyspec/lee_diagram.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/timelapse.hpp"
#include "viewer/view_requests.hpp"

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
      {viewer::viewer_setting::kHost, "--host"},
      {viewer::viewer_setting::kPort, "--port"},
      {viewer::viewer_setting::kAllowRemote, "--allow-remote"},
      {viewer::viewer_setting::kExportFolder, "--out"},
      {lee_setting::kRadiusMin, "--radius-min-um"},
      {lee_setting::kRadiusMax, "--radius-max-um"},
      {lee_setting::kAngleMin, "--angle-min"},
      {lee_setting::kAngleMax, "--angle-max"},
      {lee_setting::kWidth, "--width"},
      {lee_setting::kHeight, "--height"},
      {lee_setting::kLambdaMin, "--lambda-min"},
      {lee_setting::kLambdaMax, "--lambda-max"},
      {lee_setting::kLambdaStep, "--lambda-step"},
      {lee_setting::kTemperature, "--water-temperature"},
      {lee_setting::kSubsamples, "--angle-samples"},
      {lee_setting::kDirectory, "--out"},
      {lee_setting::kName, "--name"},
      {timelapse_setting::kStart, "--start"},
      {timelapse_setting::kEnd, "--end"},
      {timelapse_setting::kStepMinutes, "--step-minutes"},
      {timelapse_setting::kFrames, "--frames"},
  };
  return table;
}

}  // namespace skyspec::cli
