#include "job/job_spec.hpp"

#include <toml++/toml.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "base/text_format.hpp"
#include "scene/toml_limits.hpp"
#include "skyspec/error.hpp"
#include "skyspec/scene.hpp"

namespace skyspec {
namespace {

constexpr int kMaxSites = 100000;
constexpr int kMaxAxisValues = 100000;
constexpr int kMaxRandomSamples = 10000000;

std::string where(const toml::node& n, const std::string& origin) {
  const auto& s = n.source();
  if (!s.begin) return origin;
  return origin + ":" + std::to_string(s.begin.line) + ":" + std::to_string(s.begin.column);
}

std::string quoted(const std::string& s) {
  std::ostringstream o;
  o << toml::value<std::string>(s);
  return o.str();
}

// A TOML value as text that parses back to the same value ("v = " + text).
std::string value_text(const toml::node& n) {
  if (auto s = n.as_string()) return quoted(s->get());
  if (auto i = n.as_integer()) return std::to_string(i->get());
  if (auto f = n.as_floating_point()) {
    const double x = f->get();
    if (!std::isfinite(x)) return x != x ? "nan" : (x > 0 ? "inf" : "-inf");
    std::string t = format_exact(x);
    if (t.find_first_of(".eE") == std::string::npos) t += ".0";
    return t;
  }
  if (auto b = n.as_boolean()) return b->get() ? "true" : "false";
  if (auto a = n.as_array()) {
    std::string t = "[";
    for (std::size_t k = 0; k < a->size(); ++k) t += (k ? ", " : "") + value_text(*a->get(k));
    return t + "]";
  }
  std::ostringstream o;  // date-times, inline tables: TOML's own text
  if (auto dt = n.as_date_time())
    o << *dt;
  else if (auto t = n.as_table())
    o << *t;
  return o.str();
}

class Reader {
 public:
  Reader(std::string origin) : origin_(std::move(origin)) {}

  [[noreturn]] void fail(const std::string& key, const toml::node& n, const std::string& allowed) const {
    throw InputError(key, value_text(n), allowed, where(n, origin_));
  }
  void only_keys(const toml::table& t, const std::string& prefix, const std::set<std::string>& allowed) const {
    for (const auto& [k, v] : t) {
      if (allowed.count(std::string(k.str()))) continue;
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw InputError::unknown_key(prefix + std::string(k.str()), " (allowed here: " + list + ")", where(v, origin_));
    }
  }
  double number(const toml::node& n, const std::string& key, double lo, double hi) const {
    double x;
    if (auto i = n.as_integer())
      x = static_cast<double>(i->get());
    else if (auto f = n.as_floating_point())
      x = f->get();
    else
      fail(key, n, "a number from " + format_exact(lo) + " to " + format_exact(hi));
    if (!(x >= lo && x <= hi)) fail(key, n, "a number from " + format_exact(lo) + " to " + format_exact(hi));
    return x;
  }
  long long integer(const toml::node& n, const std::string& key, long long lo, long long hi) const {
    auto i = n.as_integer();
    if (!i || i->get() < lo || i->get() > hi)
      fail(key, n, "a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
    return i->get();
  }
  std::string text(const toml::node& n, const std::string& key, const std::string& allowed) const {
    auto s = n.as_string();
    if (!s || s->get().empty()) fail(key, n, allowed);
    return s->get();
  }
  std::string name(const toml::node& n, const std::string& key) const {
    const std::string allowed = "a name of letters, digits, '-' and '_' (it names files), at most 64 characters";
    const std::string s = text(n, key, allowed);
    if (s.size() > 64) fail(key, n, allowed);
    for (char c : s)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) fail(key, n, allowed);
    return s;
  }
  DateTime date_time(const toml::node& n, const std::string& key) const {
    const std::string allowed =
        "an ISO 8601 date-time with UTC offset, e.g. 2026-06-21T06:00:00+02:00 (quoted or a TOML date-time)";
    std::string t;
    if (auto dt = n.as_date_time()) {
      if (!dt->get().offset) fail(key, n, allowed + "; a bare local time is ambiguous: add Z or the offset");
      t = value_text(n);
    } else if (auto s = n.as_string()) {
      t = s->get();
    } else {
      fail(key, n, allowed);
    }
    try {
      return parse_iso8601(t, key);
    } catch (const InputError& e) {
      throw InputError(key, value_text(n), e.allowed(), where(n, origin_));
    }
  }
  // A scene key used by the job: it must exist, and not be one the job sets itself.
  std::string scene_key(const std::string& key, const toml::node& n, const std::string& what) const {
    bool known = false;
    for (const auto& [k, help] : scene_key_help())
      if (k == key) known = true;
    if (!known)
      throw InputError::unknown_key(key, " (" + what + " takes scene keys: docs/scene-keys.md)", where(n, origin_));
    if (job_owned_scene_key(key))
      throw InputError(what + "." + key, value_text(n),
                       "a scene key the job does not set itself (output.*, sun.date_time and location.* come from "
                       "[job], [[time]] and [[site]])",
                       where(n, origin_));
    return key;
  }
  const std::string& origin() const { return origin_; }

 private:
  std::string origin_;
};

// Flattens a table of scene keys ("camera.width = 128" or [scene.camera] width = 128) into
// (dotted key, node) pairs; inline tables that are values ({ start, stop, count }) stop the descent
// when `leaf_tables` is set.
void flatten(const toml::table& t, const std::string& prefix, bool leaf_tables,
             std::vector<std::pair<std::string, const toml::node*>>& out) {
  for (const auto& [k, v] : t) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    const auto* sub = v.as_table();
    if (sub && !(leaf_tables && sub->is_inline()))
      flatten(*sub, key, leaf_tables, out);
    else
      out.emplace_back(key, &v);
  }
}

void read_job_table(const Reader& r, const toml::table& t, const std::filesystem::path& base, JobSpec& job) {
  r.only_keys(
      t, "job.",
      {"name", "scene", "quality", "produce", "output", "tasks_per_chunk", "min_sun_elevation_deg", "tile_rows"});
  if (auto n = t.get("name")) job.name = r.name(*n, "job.name");
  if (auto n = t.get("scene")) {
    const std::string s = r.text(*n, "job.scene", "a preset name or the path of a scene TOML file");
    const auto presets = preset_names();
    if (std::find(presets.begin(), presets.end(), s) != presets.end()) {
      job.preset = s;
    } else {
      std::filesystem::path p(s);
      if (p.is_relative()) p = base / p;
      if (!std::filesystem::is_regular_file(p)) {
        std::string list;
        for (const auto& name : presets) list += (list.empty() ? "" : ", ") + name;
        r.fail("job.scene", *n,
               "a preset (" + list + ") or an existing scene file (relative to the job file's folder)");
      }
      job.scene_file = std::filesystem::absolute(p).lexically_normal();
    }
  }
  if (auto n = t.get("quality")) {
    const auto names = quality_names();
    job.quality = r.text(*n, "job.quality", "a quality level");
    if (std::find(names.begin(), names.end(), job.quality) == names.end())
      r.fail("job.quality", *n, "one of: draft, lean, default, high, reference");
  }
  if (auto n = t.get("produce")) {
    const std::string allowed = "a list of one or more of \"exr\", \"png\", \"irradiance\"";
    auto a = n->as_array();
    if (!a || a->empty()) r.fail("job.produce", *n, allowed);
    job.exr = job.png = job.irradiance = false;
    for (const auto& item : *a) {
      auto s = item.as_string();
      if (!s) r.fail("job.produce", item, allowed);
      if (s->get() == "exr")
        job.exr = true;
      else if (s->get() == "png")
        job.png = true;
      else if (s->get() == "irradiance")
        job.irradiance = true;
      else
        r.fail("job.produce", item, allowed);
    }
  }
  if (auto n = t.get("output")) {
    std::filesystem::path p(r.text(*n, "job.output", "a folder path"));
    job.output_directory = p;
  }
  if (auto n = t.get("tasks_per_chunk"))
    job.tasks_per_chunk = static_cast<int>(r.integer(*n, "job.tasks_per_chunk", 1, 100000));
  if (auto n = t.get("min_sun_elevation_deg"))
    job.min_sun_elevation_deg = r.number(*n, "job.min_sun_elevation_deg", -90, 90);
  if (auto n = t.get("tile_rows")) {
    job.tile_rows = static_cast<int>(r.integer(*n, "job.tile_rows", 1, 65536));
    if (!t.get("produce")) job.png = job.irradiance = false, job.exr = true;  // a tiled job's default
    if (job.png || job.irradiance || !job.exr)
      r.fail("job.tile_rows", *n,
             "a job that produces [\"exr\"] alone (its strips are merged into each frame's EXR; skyspec convert "
             "makes a PNG of a merged frame)");
  }
}

void read_sites(const Reader& r, const toml::node& node, JobSpec& job) {
  auto a = node.as_array();
  if (!a || !a->is_array_of_tables() || a->empty())
    r.fail("site", node, "[[site]] tables (name, latitude_deg, longitude_deg, altitude_m)");
  if (a->size() > kMaxSites) r.fail("site", node, "at most " + std::to_string(kMaxSites) + " sites");
  std::set<std::string> names;
  for (std::size_t k = 0; k < a->size(); ++k) {
    const auto& t = *a->get(k)->as_table();
    const std::string p = "site[" + std::to_string(k) + "].";
    r.only_keys(t, p, {"name", "latitude_deg", "longitude_deg", "altitude_m"});
    JobSite s;
    for (const char* req : {"name", "latitude_deg", "longitude_deg"})
      if (!t.get(req)) throw InputError(p + req, "(missing)", "a value for every site", where(t, r.origin()));
    s.name = r.name(*t.get("name"), p + "name");
    if (!names.insert(s.name).second) r.fail(p + "name", *t.get("name"), "a name no other site has");
    s.latitude_deg = r.number(*t.get("latitude_deg"), p + "latitude_deg", -90, 90);
    s.longitude_deg = r.number(*t.get("longitude_deg"), p + "longitude_deg", -180, 180);
    if (auto n = t.get("altitude_m")) s.altitude_m = r.number(*n, p + "altitude_m", -500, 100000);
    job.sites.push_back(s);
  }
}

void read_times(const Reader& r, const toml::node& node, JobSpec& job) {
  std::vector<const toml::table*> tables;
  if (auto t = node.as_table())
    tables.push_back(t);
  else if (auto a = node.as_array(); a && a->is_array_of_tables() && !a->empty())
    for (const auto& item : *a) tables.push_back(item.as_table());
  else
    r.fail("time", node, "a [time] table or [[time]] tables (start, end, step_minutes)");
  for (std::size_t k = 0; k < tables.size(); ++k) {
    const auto& t = *tables[k];
    const std::string p = tables.size() == 1 && node.is_table() ? "time." : "time[" + std::to_string(k) + "].";
    r.only_keys(t, p, {"start", "end", "step_minutes"});
    if (!t.get("start")) throw InputError(p + "start", "(missing)", "the first date-time", where(t, r.origin()));
    JobTimeRange range;
    range.start = r.date_time(*t.get("start"), p + "start");
    range.end = range.start;
    if (auto n = t.get("end")) {
      range.end = r.date_time(*n, p + "end");
      if (seconds_between(range.start, range.end) < 0) r.fail(p + "end", *n, "a date-time not before " + p + "start");
    }
    if (auto n = t.get("step_minutes"))
      range.step_minutes = r.number(*n, p + "step_minutes", 1.0 / 60.0, 527040);
    else if (t.get("end"))
      throw InputError(p + "step_minutes", "(missing)", "minutes between frames, with an end", where(t, r.origin()));
    job.times.push_back(range);
  }
}

void read_axes(const Reader& r, const toml::table& t, JobSpec& job) {
  std::vector<std::pair<std::string, const toml::node*>> keys;
  flatten(t, "", true, keys);
  for (const auto& [key, n] : keys) {
    const std::string name = "axes." + key;
    r.scene_key(key, *n, "axes");
    JobAxis axis{key, {}};
    if (auto a = n->as_array()) {
      if (a->empty() || a->size() > kMaxAxisValues)
        r.fail(name, *n, "a list of 1 to " + std::to_string(kMaxAxisValues) + " values, or { start, stop, count }");
      for (const auto& v : *a) axis.values.push_back(value_text(v));
    } else if (auto range = n->as_table()) {
      r.only_keys(*range, name + ".", {"start", "stop", "count"});
      for (const char* req : {"start", "stop", "count"})
        if (!range->get(req))
          throw InputError(name + "." + req, "(missing)", "start, stop and count", where(*n, r.origin()));
      const double a0 = r.number(*range->get("start"), name + ".start", -1e300, 1e300);
      const double a1 = r.number(*range->get("stop"), name + ".stop", -1e300, 1e300);
      const long long count = r.integer(*range->get("count"), name + ".count", 1, kMaxAxisValues);
      for (long long k = 0; k < count; ++k)
        axis.values.push_back(
            format_exact(count == 1 ? a0 : a0 + (a1 - a0) * static_cast<double>(k) / static_cast<double>(count - 1)));
    } else {
      r.fail(name, *n, "a list of values, or { start, stop, count }");
    }
    job.axes.push_back(std::move(axis));
  }
}

void read_random(const Reader& r, const toml::table& t, JobSpec& job) {
  r.only_keys(t, "random.", {"seed", "samples", "axes"});
  if (!t.get("samples"))
    throw InputError("random.samples", "(missing)", "the number of random samples", where(t, r.origin()));
  job.random_samples = static_cast<int>(r.integer(*t.get("samples"), "random.samples", 1, kMaxRandomSamples));
  if (auto n = t.get("seed")) job.random_seed = static_cast<std::uint64_t>(r.integer(*n, "random.seed", 0, INT64_MAX));
  auto axes = t.get("axes") ? t.get("axes")->as_table() : nullptr;
  if (!axes || axes->empty())
    throw InputError("random.axes", "(missing)", "a table of scene key = { min, max }", where(t, r.origin()));
  std::vector<std::pair<std::string, const toml::node*>> keys;
  flatten(*axes, "", true, keys);
  for (const auto& [key, n] : keys) {
    const std::string name = "random.axes." + key;
    r.scene_key(key, *n, "random.axes");
    auto range = n->as_table();
    if (!range) r.fail(name, *n, "{ min = ..., max = ... }");
    r.only_keys(*range, name + ".", {"min", "max"});
    if (!range->get("min") || !range->get("max"))
      throw InputError(name, value_text(*n), "{ min = ..., max = ... }", where(*n, r.origin()));
    JobRandomAxis axis;
    axis.key = key;
    axis.min = r.number(*range->get("min"), name + ".min", -1e300, 1e300);
    axis.max = r.number(*range->get("max"), name + ".max", axis.min, 1e300);
    axis.integer = range->get("min")->is_integer() && range->get("max")->is_integer();
    job.random_axes.push_back(axis);
  }
}

}  // namespace

bool job_owned_scene_key(const std::string& key) {
  return key.rfind("output.", 0) == 0 || key.rfind("location.", 0) == 0 || key == "sun.date_time";
}

JobSpec parse_job(const std::string& text, const std::string& origin, const std::filesystem::path& base) {
  check_toml_limits(text, "job file", origin);
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    const std::string at =
        origin + ":" + std::to_string(e.source().begin.line) + ":" + std::to_string(e.source().begin.column);
    throw InputError("job file", origin, "valid TOML (" + std::string(e.description()) + ")", at);
  }
  const Reader r(origin);
  r.only_keys(root, "", {"job", "scene", "site", "time", "axes", "random"});
  JobSpec job;
  job.name = std::filesystem::path(origin).stem().string();
  if (auto n = root.get("job")) {
    if (!n->is_table()) r.fail("job", *n, "a [job] table");
    read_job_table(r, *n->as_table(), base, job);
  }
  if (auto n = root.get("scene")) {
    if (!n->is_table()) r.fail("scene", *n, "a [scene] table of scene keys");
    std::vector<std::pair<std::string, const toml::node*>> keys;
    flatten(*n->as_table(), "", false, keys);
    std::string scene;
    for (const auto& [key, v] : keys) scene += r.scene_key(key, *v, "scene") + " = " + value_text(*v) + "\n";
    job.scene_toml = scene;
  }
  if (auto n = root.get("site")) read_sites(r, *n, job);
  if (auto n = root.get("time")) read_times(r, *n, job);
  if (auto n = root.get("axes")) {
    if (!n->is_table()) r.fail("axes", *n, "an [axes] table of scene key = [values]");
    read_axes(r, *n->as_table(), job);
  }
  if (auto n = root.get("random")) {
    if (!n->is_table()) r.fail("random", *n, "a [random] table (seed, samples, axes)");
    read_random(r, *n->as_table(), job);
  }
  for (const auto& a : job.axes)
    for (const auto& b : job.random_axes)
      if (a.key == b.key)
        throw InputError("random.axes." + b.key, "(also in [axes])", "a key swept by [axes] or by [random], not both",
                         origin);
  if (job.min_sun_elevation_deg && job.times.empty())
    throw InputError("job.min_sun_elevation_deg", format_exact(*job.min_sun_elevation_deg),
                     "a filter on [[time]] frames: give a [[time]] range", origin);
  if (job.output_directory.empty()) job.output_directory = job.name;
  job.output_directory = std::filesystem::absolute(job.output_directory).lexically_normal();
  return job;
}

JobSpec read_job_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError("JOB", "\"" + path.string() + "\"", "an existing job file (TOML)");
  std::ifstream f(path, std::ios::binary);
  std::string text;
  char buf[65536];
  while (f.read(buf, sizeof buf) || f.gcount() > 0) {
    text.append(buf, static_cast<std::size_t>(f.gcount()));
    if (text.size() > kMaxTomlBytes)
      throw InputError("JOB", "\"" + path.string() + "\"", "a job file of at most 1 MiB");
  }
  JobSpec job = parse_job(text, path.string(), std::filesystem::absolute(path).parent_path());
  job.file = std::filesystem::absolute(path).lexically_normal();
  return job;
}

}  // namespace skyspec
