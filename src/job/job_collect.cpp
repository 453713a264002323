#include "job/job_collect.hpp"

#include <cstdio>
#include <fstream>
#include <map>

#include "base/atomic_file.hpp"
#include "base/output_lock.hpp"
#include "base/sha256.hpp"
#include "io/exr_merge.hpp"
#include "job/irradiance_netcdf.hpp"
#include "job/task_record.hpp"
#include "render/irradiance.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

using nlohmann::json;

constexpr std::size_t kFailuresListed = 5;

std::string csv_number(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

std::string csv_text(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string csv_value(const json& v) {
  if (v.is_number()) return csv_number(v.get<double>());
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_string()) return csv_text(v.get<std::string>());
  return csv_text(v.dump());
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  AtomicOutputFile file(path);
  {
    std::ofstream f(file.temporary_path(), std::ios::binary);
    f << text;
    if (!f.flush()) throw IoError("cannot write " + path.string());
  }
  file.commit();
}

// The irradiance table (irradiance_<site>.csv): per task its sun, swept keys, the band the W m^-2
// columns integrate over, then every quantity of irradiance_quantities(): the broadband ones when
// the first row has them (a row without them then leaves their fields empty).
bool with_broadband(const json& first) {
  for (const IrradianceQuantity& q : irradiance_quantities())
    if (q.of_broadband) return first.at("irradiance").contains(q.key);
  return false;
}

std::string table_header(const JobPlan& plan, const json& first) {
  std::string h = "task,date_time,sun_elevation_deg,sun_azimuth_deg";
  for (const auto& [key, value] : plan.combinations.front()) h += "," + key;
  h += ",band_min_nm,band_max_nm";
  const auto& wl = first.at("irradiance").at("wavelengths_nm");
  for (const IrradianceQuantity& q : irradiance_quantities()) {
    if (q.of_broadband && !with_broadband(first)) continue;
    if (!q.spectral())
      h += std::string(",") + q.key;
    else
      for (const auto& w : wl) h += std::string(",") + q.key + "_" + csv_number(w.get<double>());
  }
  return h + "\n";
}

std::string table_row(const JobPlan& plan, const json& r, bool broadband) {
  std::string row = r.at("id").get<std::string>() + "," + csv_text(r.value("date_time", std::string())) + "," +
                    csv_number(r.at("sun_elevation_deg").get<double>()) + "," +
                    csv_number(r.at("sun_azimuth_deg").get<double>());
  for (const auto& [key, value] : plan.combinations.front()) row += "," + csv_value(r.at("parameters").at(key));
  const auto& irr = r.at("irradiance");
  const auto& wl = irr.at("wavelengths_nm");
  row += "," + csv_number(wl.front().get<double>()) + "," + csv_number(wl.back().get<double>());
  for (const IrradianceQuantity& q : irradiance_quantities()) {
    if (q.of_broadband && !broadband) continue;
    if (q.of_broadband && !irr.contains(q.key))
      row += ",";
    else if (!q.spectral())
      row += "," + csv_number(irr.at(q.key).get<double>());
    else
      for (const auto& v : irr.at(q.key)) row += "," + csv_number(v.get<double>());
  }
  return row + "\n";
}

// The frame's strips merged into frames/<frame id>.exr, unless its record says that file was made
// from exactly these strips and it still has its checksum. Returns the frame's record.
json merge_frame(const JobPlan& plan, int frame, const std::vector<json>& records, JobSummary& summary) {
  const auto dir = plan.job.output_directory / "frames";
  const auto exr = dir / (JobPlan::frame_id(frame) + ".exr"), record_path = dir / (JobPlan::frame_id(frame) + ".json");
  const TaskRange range = plan.frame_tasks[frame];
  json inputs = json::array();
  std::vector<std::filesystem::path> tiles;
  for (int k = range.first; k < range.last; ++k) {
    const json& f = records[k].at("files").at(0);
    inputs.push_back({{"task", plan.tasks[k].id()}, {"sha256", f.at("sha256")}});
    tiles.push_back(plan.job.output_directory / f.at("path").get<std::string>());
  }
  std::ifstream old(record_path);
  if (old) {
    const json previous = json::parse(old, nullptr, false);
    std::error_code ec;
    if (!previous.is_discarded() && previous.value("inputs", json()) == inputs &&
        std::filesystem::file_size(exr, ec) == previous.at("file").value("bytes", std::uintmax_t{0}) && !ec &&
        sha256_file_hex(exr) == previous.at("file").value("sha256", std::string())) {
      ++summary.frames_kept;
      return previous;
    }
  }
  std::filesystem::create_directories(dir);
  merge_spectral_exr_tiles(tiles, exr);
  const json record = {{"frame", frame},
                       {"id", JobPlan::frame_id(frame)},
                       {"inputs", inputs},
                       {"file",
                        {{"path", std::filesystem::relative(exr, plan.job.output_directory).generic_string()},
                         {"bytes", std::filesystem::file_size(exr)},
                         {"sha256", sha256_file_hex(exr)}}}};
  write_text_atomically(record_path, record.dump() + "\n");
  ++summary.frames_merged;
  return record;
}

}  // namespace

std::string JobSummary::describe() const {
  std::string s = std::to_string(ok) + " task(s) done";
  if (failed) s += ", " + std::to_string(failed) + " failed";
  if (missing) s += ", " + std::to_string(missing) + " not run";
  if (damaged) s += ", " + std::to_string(damaged) + " with a damaged record or missing files (run the job again)";
  if (frames_merged || frames_kept || frames_incomplete)
    s += "; frames: " + std::to_string(frames_merged) + " merged, " + std::to_string(frames_kept) +
         " already merged, " + std::to_string(frames_incomplete) + " waiting for strips";
  for (const auto& f : failures) s += "\n  " + f;
  if (failed > static_cast<int>(failures.size())) s += "\n  ... (every error is in manifest.jsonl)";
  return s;
}

JobSummary collect_job(const JobPlan& plan) {
  JobSummary summary;
  std::string manifest;
  std::map<std::string, std::string> tables;                               // site -> CSV text
  std::map<std::string, std::pair<int, std::vector<const json*>>> series;  // site -> (its index, its rows)
  std::vector<json> records(plan.tasks.size());
  for (const auto& task : plan.tasks) {
    std::string damaged;
    json r = read_task_record(plan, task, &damaged);  // validated: records are untrusted input
    // An ok record whose files are gone or changed size is not done either (the checksums are
    // checked again by a resumed run; sizes here, so that collecting stays quick).
    if (!r.is_null() && r.value("status", "") == "ok")
      for (const auto& f : r.at("files")) {
        std::error_code ec;
        const auto size = std::filesystem::file_size(plan.job.output_directory / f.at("path").get<std::string>(), ec);
        if (ec || size != f.at("bytes").get<std::uintmax_t>()) {
          damaged = "its file " + f.at("path").get<std::string>() + (ec ? " is missing" : " is not the size recorded");
          r = nullptr;
          break;
        }
      }
    records[task.index] = r;  // read once; the tables below point into `records`
    if (r.is_null()) {
      json entry = {{"task", task.index}, {"id", task.id()}, {"site", plan.site_name(task)}};
      if (damaged.empty()) {
        ++summary.missing;
        entry["status"] = "missing";
      } else {
        ++summary.damaged;
        entry["status"] = "damaged";
        entry["error"] = damaged;
        if (summary.damaged_records.size() < kFailuresListed)
          summary.damaged_records.push_back(task.id() + ": " + damaged);
      }
      manifest += entry.dump() + "\n";
      continue;
    }
    manifest += r.dump() + "\n";
    if (r.value("status", "") != "ok") {
      ++summary.failed;
      if (summary.failures.size() < kFailuresListed)
        summary.failures.push_back(task.id() + ": " + r.value("error", std::string("(no error recorded)")));
      continue;
    }
    ++summary.ok;
    if (!plan.job.irradiance || !r.contains("irradiance")) continue;
    try {
      auto& table = tables[plan.site_name(task)];
      auto& rows = series[plan.site_name(task)];
      if (table.empty()) table = table_header(plan, r);
      table += table_row(plan, r, with_broadband(rows.second.empty() ? r : *rows.second.front()));
      rows.first = task.site;
      rows.second.push_back(&records[task.index]);
    } catch (const json::exception& e) {
      throw IoError("the record of task " + task.id() + " is damaged (" + e.what() + "): remove " +
                    task_record_path(plan, task).string() + " and run the job again");
    }
  }
  const auto& out = plan.job.output_directory;
  std::filesystem::create_directories(out);
  // Temporaries of the manifest, tables and frames that a killed collect left (their process gone).
  remove_stale_temporaries(out, "");
  remove_stale_temporaries(out / "frames", "");
  write_text_atomically(out / "manifest.jsonl", manifest);
  if (plan.job.tile_rows > 0) {
    std::string frames;
    for (int f = 0; f < static_cast<int>(plan.frame_tasks.size()); ++f) {
      bool complete = true;
      for (int k = plan.frame_tasks[f].first; k < plan.frame_tasks[f].last; ++k)
        complete &= !records[k].is_null() && records[k].value("status", "") == "ok";
      if (!complete) {
        ++summary.frames_incomplete;
        frames += json{{"frame", f}, {"id", JobPlan::frame_id(f)}, {"status", "incomplete"}}.dump() + "\n";
        continue;
      }
      try {
        frames += merge_frame(plan, f, records, summary).dump() + "\n";
      } catch (const json::exception& e) {
        throw IoError("the records of frame " + JobPlan::frame_id(f) + " are damaged (" + e.what() + ")");
      }
    }
    write_text_atomically(out / "frames.jsonl", frames);
  }
  for (const auto& [site, text] : tables) {
    const auto path = out / ("irradiance_" + site + ".csv");
    write_text_atomically(path, text);
    summary.tables.push_back(path);
    const auto nc = out / ("irradiance_" + site + ".nc");
    try {
      write_irradiance_netcdf(nc, plan, series[site].first, series[site].second);
    } catch (const json::exception& e) {
      throw IoError("a record of site " + site + " is damaged (" + e.what() + ")");
    }
    summary.tables.push_back(nc);
  }
  return summary;
}

}  // namespace skyspec
