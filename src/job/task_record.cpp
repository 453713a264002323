#include "job/task_record.hpp"

#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "base/atomic_file.hpp"
#include "base/cancellation.hpp"
#include "base/sha256.hpp"
#include "colour/display_pipeline.hpp"
#include "physics/date_time.hpp"
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
  json out = {{"wavelengths_nm", r.wavelengths_nm}};
  for (const IrradianceQuantity& q : irradiance_quantities())
    if (q.present_in(r)) out[q.key] = q.spectral() ? spectrum_json(q.spectrum(r)) : json(q.value(r));
  return out;
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

std::unique_ptr<OutputLock> try_lock_task(const JobPlan& plan, const JobTask& task) {
  return OutputLock::try_lock(plan.task_directory(), task.id() + ".task");
}

json run_task(const JobPlan& plan, const JobTask& task, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  json record = {{"task", task.index},           {"id", task.id()},
                 {"site", plan.site_name(task)}, {"date_time", task.time ? to_iso8601(*task.time) : std::string()},
                 {"parameters", json::object()}, {"skyspec_version", version_string()},
                 {"host", host_name()}};
  for (const auto& [key, value] : plan.combinations.at(task.combination))
    record["parameters"][key] = parameter_json(value);
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
            if (plan.job.irradiance) irradiance = irradiance_report(scene, r);
          },
          task.tile);
      written = out.files();  // every output of the task, polarisation files included
      record["exposure_ev"] = out.preview_ev;
    } else {
      Scene one = scene;  // only the camera position matters
      one.camera.width = one.camera.height = 1;
      irradiance = irradiance_report(one, SkyRenderer(one));
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

namespace {

bool is_hex_digest(const json& v) {
  if (!v.is_string() || v.get_ref<const std::string&>().size() != 64) return false;
  for (char c : v.get_ref<const std::string&>())
    if (!std::isxdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

bool is_finite_number(const json& v) { return v.is_number() && std::isfinite(v.get<double>()); }

// A relative path that stays inside the job's folder: not absolute, no "..", no empty name.
bool is_path_inside_job(const json& v) {
  if (!v.is_string() || v.get_ref<const std::string&>().empty()) return false;
  const std::filesystem::path p(v.get_ref<const std::string&>());
  if (p.is_absolute() || p.has_root_name() || p.has_root_directory()) return false;
  for (const auto& part : p)
    if (part == ".." || part.empty()) return false;
  return true;
}

}  // namespace

std::string record_problem(const JobPlan& plan, const JobTask& task, const json& r) {
  if (!r.is_object()) return "it is not a JSON object";
  if (!r.contains("task") || !r.at("task").is_number_integer() || r.at("task").get<long long>() != task.index)
    return "its \"task\" is not " + std::to_string(task.index);
  if (!r.contains("id") || !r.at("id").is_string() || r.at("id").get<std::string>() != task.id())
    return "its \"id\" is not \"" + task.id() + "\"";
  const std::string status =
      r.contains("status") && r.at("status").is_string() ? r.at("status").get<std::string>() : "";
  if (status != "ok" && status != "failed") return "its \"status\" is neither \"ok\" nor \"failed\"";
  if (r.contains("date_time") && !r.at("date_time").is_string()) return "its \"date_time\" is not text";
  if (r.contains("date_time") && !r.at("date_time").get<std::string>().empty()) {
    try {
      parse_iso8601(r.at("date_time").get<std::string>(), "date_time");
    } catch (const InputError&) {
      return "its \"date_time\" " + r.at("date_time").get<std::string>() + " is not an ISO 8601 date-time";
    }
  }
  if (!r.contains("files") || !r.at("files").is_array()) return "it has no \"files\" list";
  for (const auto& f : r.at("files")) {
    if (!f.is_object() || !f.contains("path") || !is_path_inside_job(f.at("path")))
      return "a file's \"path\" is not a relative path inside the job's folder";
    if (!f.contains("bytes") || !f.at("bytes").is_number_unsigned()) return "a file's \"bytes\" is not a whole number";
    if (!f.contains("sha256") || !is_hex_digest(f.at("sha256"))) return "a file's \"sha256\" is not 64 hex digits";
  }
  if (status != "ok") return "";
  for (const char* angle : {"sun_elevation_deg", "sun_azimuth_deg"})
    if (!r.contains(angle) || !is_finite_number(r.at(angle)))
      return std::string("its \"") + angle + "\" is not a finite number";
  if (r.contains("irradiance")) {
    const json& irr = r.at("irradiance");
    if (!irr.is_object() || !irr.contains("wavelengths_nm") || !irr.at("wavelengths_nm").is_array())
      return "its irradiance has no wavelengths";
    const Scene scene = task_scene(plan, task);
    const std::vector<double> grid = make_wavelength_grid(scene).nanometres();
    const json& wl = irr.at("wavelengths_nm");
    if (wl.size() != grid.size())
      return "its irradiance has " + std::to_string(wl.size()) + " wavelengths, not the scene's " +
             std::to_string(grid.size());
    for (std::size_t k = 0; k < wl.size(); ++k)
      if (!is_finite_number(wl[k]) || std::abs(wl[k].get<double>() - grid[k]) > 1e-9 * grid[k])
        return "its irradiance's wavelengths are not the scene's";
    // The broadband values are there exactly when the task's scene asks for them.
    for (const IrradianceQuantity& q : irradiance_quantities()) {
      const bool expected = !q.of_broadband || scene.irradiance.broadband;
      if (expected && !irr.contains(q.key)) return std::string("its irradiance has no \"") + q.key + "\"";
      if (!expected && irr.contains(q.key))
        return std::string("its irradiance has \"") + q.key + "\", which its scene does not ask for";
    }
    for (const auto& [key, value] : irr.items()) {
      if (key == "wavelengths_nm") continue;
      if (value.is_array()) {
        if (value.size() != grid.size())
          return "its \"" + key + "\" has " + std::to_string(value.size()) + " values for " +
                 std::to_string(grid.size()) + " wavelengths";
        for (const auto& v : value)
          if (!is_finite_number(v)) return "its \"" + key + "\" has a value that is not a finite number";
      } else if (!is_finite_number(value)) {
        return "its \"" + key + "\" is not a finite number";
      }
    }
  }
  return "";
}

std::vector<std::string> expected_task_files(const JobPlan& plan, const JobTask& task) {
  std::vector<std::string> files;
  if (!plan.job.exr && !plan.job.png) return files;
  Scene scene = task_scene(plan, task);
  for (const auto& path : render_output_paths(scene, DisplaySettings{}).files()) {
    if (task.tile && path.extension() != ".exr") continue;  // a tile writes its spectral EXR alone
    if (task.tile && path.filename().string().find("-polarisation") != std::string::npos) continue;
    files.push_back(std::filesystem::relative(path, plan.job.output_directory).generic_string());
  }
  return files;
}

json read_task_record(const JobPlan& plan, const JobTask& task, std::string* damaged) {
  const auto path = task_record_path(plan, task);
  std::error_code ec;
  if (!std::filesystem::exists(std::filesystem::symlink_status(path, ec))) return nullptr;
  const auto fail = [damaged](const std::string& why) {
    if (damaged) *damaged = why;
    return json(nullptr);
  };
  if (!is_regular_input(path)) return fail("its record is not a regular file");
  std::ifstream f(path, std::ios::binary);
  if (!f) return fail("its record cannot be read");
  std::stringstream text;
  text << f.rdbuf();
  const json j = json::parse(text.str(), nullptr, false);
  if (j.is_discarded()) return fail("its record is not valid JSON");
  if (const std::string problem = record_problem(plan, task, j); !problem.empty())
    return fail("its record is damaged: " + problem);
  return j;
}

bool task_done(const JobPlan& plan, const JobTask& task, std::string& why) {
  std::string damaged;
  const json r = read_task_record(plan, task, &damaged);
  if (r.is_null()) return why = damaged.empty() ? "no record" : damaged, false;
  if (r.value("status", "") != "ok") return why = "it failed: " + r.value("error", std::string("?")), false;
  // Every output the task's scene asks for must be listed ("files": [] is not done).
  for (const auto& expected : expected_task_files(plan, task)) {
    bool listed = false;
    for (const auto& f : r.at("files")) listed |= f.at("path").get<std::string>() == expected;
    if (!listed) return why = "its record does not list " + expected, false;
  }
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
