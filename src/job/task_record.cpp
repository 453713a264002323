#include "job/task_record.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "base/atomic_file.hpp"
#include "base/cancellation.hpp"
#include "base/sha256.hpp"
#include "colour/display_pipeline.hpp"
#include "render/irradiance.hpp"
#include "skyspec/error.hpp"
#include "skyspec/render.hpp"
#include "skyspec/version.hpp"

namespace skyspec {
namespace {

using nlohmann::json;

// A swept value's TOML text as JSON: numbers, booleans and strings typed, anything else as text.
json parameter_json(const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (!text.empty() && *end == '\0' && std::isfinite(x)) return x;
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"') return text.substr(1, text.size() - 2);
  return text;
}

json spectrum_json(const SpectrumD& s) {
  json a = json::array();
  for (Eigen::Index k = 0; k < s.size(); ++k) a.push_back(s[k]);
  return a;
}

json irradiance_json(const IrradianceReport& r) {
  const SpectrumD global = r.direct_horizontal + r.diffuse_horizontal;
  return {{"direct_normal_W_m2", r.direct_normal_W_m2},
          {"direct_horizontal_W_m2", r.direct_horizontal_W_m2},
          {"diffuse_horizontal_W_m2", r.diffuse_horizontal_W_m2},
          {"direct_normal_lux", r.direct_normal_lux},
          {"direct_horizontal_lux", r.direct_horizontal_lux},
          {"diffuse_horizontal_lux", r.diffuse_horizontal_lux},
          {"global_horizontal_lux", r.global_horizontal_lux()},
          {"wavelengths_nm", r.wavelengths_nm},
          {"direct_normal_W_m2_nm", spectrum_json(r.direct_normal)},
          {"diffuse_horizontal_W_m2_nm", spectrum_json(r.diffuse_horizontal)},
          {"global_horizontal_W_m2_nm", spectrum_json(global)}};
}

std::string host_name() {
  char buf[256] = {};
  if (gethostname(buf, sizeof buf - 1) != 0) return "";
  return buf;
}

json file_entry(const JobPlan& plan, const std::filesystem::path& path) {
  return {{"path", std::filesystem::relative(path, plan.job.output_directory).generic_string()},
          {"bytes", std::filesystem::file_size(path)},
          {"sha256", sha256_file_hex(path)}};
}

void write_record(const std::filesystem::path& path, const json& record) {
  AtomicOutputFile file(path);
  {
    std::ofstream f(file.temporary_path(), std::ios::binary);
    f << record.dump() << "\n";
    if (!f.flush()) throw IoError("cannot write " + path.string());
  }
  file.commit();
}

}  // namespace

std::filesystem::path task_record_path(const JobPlan& plan, const JobTask& task) {
  return plan.task_directory() / (task.id() + ".json");
}

std::string task_scene_digest(const Scene& scene) {
  // As the files record it: without the output folder (a job's folder moved elsewhere resumes)
  // and the threads (any worker may run the task).
  return sha256_hex(scene_to_toml(scene, SceneTomlKeys::Recorded));
}

json run_task(const JobPlan& plan, const JobTask& task, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  json record = {{"task", task.index},
                 {"id", task.id()},
                 {"site", plan.site_name(task)},
                 {"date_time", task.time ? to_iso8601(*task.time) : std::string()},
                 {"parameters", json::object()},
                 {"skyspec_version", version_string()},
                 {"host", host_name()}};
  for (const auto& [key, value] : plan.combinations.at(task.combination)) record["parameters"][key] = parameter_json(value);
  if (task.tile) {
    record["frame"] = task.frame;
    record["tile"] = {task.tile->x0, task.tile->x1, task.tile->y0, task.tile->y1};
  }
  std::vector<std::filesystem::path> written;
  try {
    Scene scene = task_scene(plan, task);
    if (threads > 0) scene.render.threads = threads;  // not recorded in the files (SceneTomlKeys::Recorded)
    record["sun_elevation_deg"] = scene.sun.elevation_deg;
    record["sun_azimuth_deg"] = scene.sun.azimuth_deg;
    record["scene_sha256"] = task_scene_digest(scene);
    std::filesystem::create_directories(plan.task_directory());
    std::optional<IrradianceReport> irradiance;
    if (plan.job.exr || plan.job.png) {
      const RenderOutputs out = render_scene_to_files(
          scene, DisplaySettings{}, {},
          [&](const SkyRenderer& r) {
            if (plan.job.irradiance) irradiance = irradiance_at_camera(r);
          },
          task.tile);
      written = out.files();  // every output of the task, polarisation files included
      record["exposure_ev"] = out.preview_ev;
    } else {
      Scene one = scene;  // only the camera position matters
      one.camera.width = one.camera.height = 1;
      irradiance = irradiance_at_camera(SkyRenderer(one));
    }
    json files = json::array();
    for (const auto& p : written) files.push_back(file_entry(plan, p));
    record["files"] = files;
    if (irradiance) record["irradiance"] = irradiance_json(*irradiance);
    record["status"] = "ok";
  } catch (const Cancelled&) {
    throw;
  } catch (const std::exception& e) {  // InputError, IoError, Error, bad_alloc: recorded, the job goes on
    for (const auto& p : written) std::filesystem::remove(p);
    record["status"] = "failed";
    record["error"] = e.what();
    record["files"] = json::array();
  }
  record["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_record(task_record_path(plan, task), record);
  return record;
}

json read_task_record(const JobPlan& plan, const JobTask& task) {
  std::ifstream f(task_record_path(plan, task), std::ios::binary);
  if (!f) return nullptr;
  std::stringstream text;
  text << f.rdbuf();
  const json j = json::parse(text.str(), nullptr, false);
  return j.is_discarded() || !j.is_object() ? json(nullptr) : j;
}

bool task_done(const JobPlan& plan, const JobTask& task, std::string& why) {
  const json r = read_task_record(plan, task);
  if (r.is_null()) return why = "no record", false;
  if (r.value("status", "") != "ok") return why = "it failed: " + r.value("error", std::string("?")), false;
  try {
    if (r.value("scene_sha256", "") != task_scene_digest(task_scene(plan, task)))
      return why = "its record is of another scene (the job changed)", false;
    for (const auto& f : r.at("files")) {
      const auto path = plan.job.output_directory / f.at("path").get<std::string>();
      std::error_code ec;
      const auto size = std::filesystem::file_size(path, ec);
      if (ec) return why = f.at("path").get<std::string>() + " is missing", false;
      if (size != f.at("bytes").get<std::uintmax_t>() || sha256_file_hex(path) != f.at("sha256").get<std::string>())
        return why = f.at("path").get<std::string>() + " does not match its checksum", false;
    }
  } catch (const json::exception&) {
    return why = "its record is damaged", false;
  } catch (const IoError& e) {
    return why = e.what(), false;
  }
  return true;
}

}  // namespace skyspec
