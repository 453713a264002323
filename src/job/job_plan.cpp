#include "job/job_plan.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "base/text_format.hpp"
#include "physics/solar_position.hpp"
#include "skyspec/error.hpp"

namespace skyspec {
namespace {

constexpr long long kMaxTasks = 2000000;

// SplitMix64 (Steele, Lea & Flood 2014): a sample's random numbers depend only on the seed, the
// sample and the axis, never on the order in which they are drawn or on the C++ library.
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

double uniform01(std::uint64_t seed, std::uint64_t sample, std::uint64_t axis) {
  const std::uint64_t x = splitmix64(splitmix64(splitmix64(seed) ^ sample) ^ axis);
  return static_cast<double>(x >> 11) * 0x1.0p-53;
}

std::string random_value(const JobRandomAxis& a, double u) {
  if (a.integer) {
    const double span = a.max - a.min + 1.0;
    return format_exact(std::min(a.max, a.min + std::floor(u * span)));
  }
  return format_exact(a.min + u * (a.max - a.min));
}

std::vector<JobParameters> combinations_of(const JobSpec& job) {
  std::vector<JobParameters> combos{JobParameters{}};
  for (const auto& axis : job.axes) {
    std::vector<JobParameters> next;
    if (static_cast<double>(combos.size()) * static_cast<double>(axis.values.size()) > kMaxTasks)
      throw InputError("axes", "(" + std::to_string(combos.size() * axis.values.size()) + " combinations)",
                       "at most " + std::to_string(kMaxTasks) + " combinations");
    for (const auto& c : combos)
      for (const auto& v : axis.values) {
        JobParameters p = c;
        p.emplace_back(axis.key, v);
        next.push_back(std::move(p));
      }
    combos = std::move(next);
  }
  if (job.random_samples > 0) {
    if (static_cast<double>(combos.size()) * job.random_samples > kMaxTasks)
      throw InputError("random.samples", std::to_string(job.random_samples),
                       "at most " + std::to_string(kMaxTasks) + " combinations with [axes]");
    std::vector<JobParameters> next;
    for (const auto& c : combos)
      for (int s = 0; s < job.random_samples; ++s) {
        JobParameters p = c;
        for (std::size_t a = 0; a < job.random_axes.size(); ++a)
          p.emplace_back(
              job.random_axes[a].key,
              random_value(job.random_axes[a], uniform01(job.random_seed, static_cast<std::uint64_t>(s), a)));
        next.push_back(std::move(p));
      }
    combos = std::move(next);
  }
  return combos;
}

SceneLoader base_loader(const JobSpec& job) {
  SceneLoader l(job.preset);
  if (!job.quality.empty()) l.apply_quality(job.quality, "job.quality");
  if (!job.scene_file.empty()) l.apply_file(job.scene_file.string());
  if (!job.scene_toml.empty()) l.apply_toml(job.scene_toml, job.file.string() + " [scene]");
  return l;
}

// Where a value of the job file came from, for the scene loader's messages: "JOB.toml: axes.KEY".
std::string origin_in(const JobSpec& job, const std::string& key) {
  return job.file.empty() ? key : job.file.string() + ": " + key;
}

std::string vec_text(const Vec3& v) {
  return "[" + format_exact(v.x()) + ", " + format_exact(v.y()) + ", " + format_exact(v.z()) + "]";
}

void apply_site(SceneLoader& l, const Scene& base, const JobSite& site, const std::string& origin) {
  l.apply_override("location.latitude_deg", format_exact(site.latitude_deg), origin + ".latitude_deg");
  l.apply_override("location.longitude_deg", format_exact(site.longitude_deg), origin + ".longitude_deg");
  if (site.altitude_m != 0.0) {
    Vec3 p = base.camera.position_m;
    p.z() += site.altitude_m;
    l.apply_override("camera.position_m", vec_text(p), origin + ".altitude_m");
  }
}

}  // namespace

namespace {
std::string task_name(const JobSpec& job, int index) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%0*d", job.task_digits, index);
  return job.task_prefix + buf;
}
}  // namespace

int JobPlan::chunk_count() const {
  const int per = job.tasks_per_chunk;
  return static_cast<int>((tasks.size() + per - 1) / per);
}

TaskRange JobPlan::chunk(int k) const {
  const int per = job.tasks_per_chunk, n = static_cast<int>(tasks.size());
  return {std::min(n, k * per), std::min(n, (k + 1) * per)};
}

TaskRange JobPlan::shard(int i, int n) const {
  const long long total = static_cast<long long>(tasks.size());
  return {static_cast<int>(total * (i - 1) / n), static_cast<int>(total * i / n)};
}

std::filesystem::path JobPlan::task_directory() const {
  return job.task_folder.empty() ? job.output_directory : job.output_directory / job.task_folder;
}

std::string JobPlan::frame_id(int frame) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "f%06d", frame);
  return buf;
}

std::string JobPlan::site_name(const JobTask& task) const {
  return task.site < 0 ? std::string("scene") : job.sites[task.site].name;
}

JobPlan plan_job(const JobSpec& job) {
  JobPlan plan;
  plan.job = job;
  const SceneLoader base = base_loader(job);
  const Scene base_scene = base.finish();
  if (job.irradiance && base_scene.render.path != RenderSpec::Path::Spectral)
    throw InputError("job.produce", "\"irradiance\"",
                     "a spectral scene (render.path = \"spectral\"): illuminance needs the colour-matching functions",
                     job.file.string());
  // Every site and every swept value, each on the base scene, through the scene's own checks.
  for (std::size_t k = 0; k < job.sites.size(); ++k) {
    SceneLoader l = base;
    apply_site(l, base_scene, job.sites[k], origin_in(job, "site[" + std::to_string(k) + "]"));
    l.finish();
  }
  for (const auto& axis : job.axes)
    for (const auto& v : axis.values) {
      SceneLoader l = base;
      l.apply_override(axis.key, v, origin_in(job, "axes." + axis.key));
      l.finish();
    }
  for (const auto& axis : job.random_axes)
    for (double x : {axis.min, axis.max}) {
      SceneLoader l = base;
      l.apply_override(axis.key, format_exact(x), origin_in(job, "random.axes." + axis.key));
      l.finish();
    }
  plan.combinations = combinations_of(job);

  // The frames of each site, with the sun's apparent elevation (NREL SPA, as the scene computes it).
  struct Frame {
    std::optional<DateTime> time;
    double elevation = 0.0;
  };
  const int site_count = job.sites.empty() ? 1 : static_cast<int>(job.sites.size());
  std::vector<std::vector<Frame>> frames(site_count);
  for (int s = 0; s < site_count; ++s) {
    if (job.times.empty()) {
      frames[s].push_back({std::nullopt, base_scene.sun.elevation_deg});
      continue;
    }
    Observer where;
    where.latitude_deg = job.sites.empty() ? base_scene.location.latitude_deg : job.sites[s].latitude_deg;
    where.longitude_deg = job.sites.empty() ? base_scene.location.longitude_deg : job.sites[s].longitude_deg;
    where.altitude_m = base_scene.camera.position_m.z() + (job.sites.empty() ? 0.0 : job.sites[s].altitude_m);
    SolarPositionOptions opt;
    opt.refraction = base_scene.sun.refraction;
    for (std::size_t r = 0; r < job.times.size(); ++r) {
      const auto& range = job.times[r];
      const double span = seconds_between(range.start, range.end);
      const long long n = static_cast<long long>(std::floor(span / (range.step_minutes * 60.0) + 1e-9)) + 1;
      if (n * static_cast<long long>(plan.combinations.size()) * site_count > kMaxTasks)
        throw InputError("time[" + std::to_string(r) + "].step_minutes", format_exact(range.step_minutes),
                         "a step giving at most " + std::to_string(kMaxTasks) + " tasks in all (this gives " +
                             std::to_string(n * static_cast<long long>(plan.combinations.size()) * site_count) + ")",
                         job.file.string());
      for (long long k = 0; k < n; ++k) {
        const DateTime t = add_seconds(range.start, static_cast<double>(k) * range.step_minutes * 60.0);
        const double el = solar_position(t, where, opt).elevation_deg;
        if (job.min_sun_elevation_deg && el < *job.min_sun_elevation_deg) continue;
        frames[s].push_back({t, el});
      }
    }
  }
  for (int s = 0; s < site_count; ++s)
    for (int c = 0; c < static_cast<int>(plan.combinations.size()); ++c) {
      // With job.tile_rows, the strips of each frame: the image's size as this parameter set has it.
      std::vector<std::optional<PixelBounds>> strips{std::nullopt};
      if (job.tile_rows > 0) {
        SceneLoader l = base;
        for (const auto& [key, value] : plan.combinations[c])
          l.apply_override(key, value, origin_in(job, "axes." + key));
        const Scene sized = l.finish();
        strips.clear();
        for (int y = 0; y < sized.camera.height; y += job.tile_rows)
          strips.push_back(PixelBounds{0, sized.camera.width, y, std::min(sized.camera.height, y + job.tile_rows)});
      }
      for (const auto& f : frames[s]) {
        const int first = static_cast<int>(plan.tasks.size());
        for (const auto& strip : strips) {
          if (static_cast<long long>(plan.tasks.size()) >= kMaxTasks)
            throw InputError("job.tile_rows", std::to_string(job.tile_rows),
                             "strips giving at most " + std::to_string(kMaxTasks) + " tasks in all", job.file.string());
          JobTask t;
          t.index = static_cast<int>(plan.tasks.size());
          t.site = job.sites.empty() ? -1 : s;
          t.time = f.time;
          t.combination = c;
          t.sun_elevation_deg = f.elevation;
          t.frame = static_cast<int>(plan.frame_tasks.size());
          t.tile = strip;
          t.name = task_name(job, t.index);
          plan.tasks.push_back(t);
        }
        plan.frame_tasks.push_back({first, static_cast<int>(plan.tasks.size())});
      }
    }
  if (plan.tasks.empty())
    throw InputError("job.min_sun_elevation_deg", format_exact(job.min_sun_elevation_deg.value_or(0.0)),
                     "a limit some frame reaches (no frame of the job has the sun this high)", job.file.string());
  return plan;
}

Scene task_scene(const JobPlan& plan, const JobTask& task) {
  const JobSpec& job = plan.job;
  SceneLoader l = base_loader(job);
  const Scene base = l.finish();
  if (task.site >= 0)
    apply_site(l, base, job.sites[task.site], origin_in(job, "site[" + std::to_string(task.site) + "]"));
  if (task.time) l.apply_override("sun.date_time", "\"" + to_iso8601(*task.time) + "\"", origin_in(job, "time"));
  for (const auto& [key, value] : plan.combinations.at(task.combination))
    l.apply_override(key, value, origin_in(job, "axes." + key));
  l.apply_override("output.directory", plan.task_directory().string(), "job.output");
  l.apply_override("output.name", task.id(), "task id");
  l.apply_override("output.exr", job.exr ? "true" : "false", "job.produce");
  l.apply_override("output.png", job.png ? "true" : "false", "job.produce");
  if (job.exposure_ev) l.apply_override("output.exposure_ev", format_exact(*job.exposure_ev), "the job's exposure");
  return l.finish();
}

std::pair<int, int> parse_shard(const std::string& text, const std::string& setting) {
  const auto slash = text.find('/');
  const std::string allowed = "I/N with 1 <= I <= N <= 1000000, e.g. 3/8 (the third of eight shards)";
  if (slash == std::string::npos) throw InputError(setting, "\"" + text + "\"", allowed);
  char* end = nullptr;
  const std::string a = text.substr(0, slash), b = text.substr(slash + 1);
  const long i = std::strtol(a.c_str(), &end, 10);
  if (a.empty() || *end) throw InputError(setting, "\"" + text + "\"", allowed);
  const long n = std::strtol(b.c_str(), &end, 10);
  if (b.empty() || *end || n < 1 || n > 1000000 || i < 1 || i > n)
    throw InputError(setting, "\"" + text + "\"", allowed);
  return {static_cast<int>(i), static_cast<int>(n)};
}

TaskRange parse_task_range(const std::string& text, int count, const std::string& setting) {
  const std::string allowed = "an index or A-B (inclusive), from 0 to " + std::to_string(count - 1);
  const auto dash = text.find('-');
  const std::string a = text.substr(0, dash), b = dash == std::string::npos ? a : text.substr(dash + 1);
  char* end = nullptr;
  const long first = std::strtol(a.c_str(), &end, 10);
  if (a.empty() || *end) throw InputError(setting, "\"" + text + "\"", allowed);
  const long last = std::strtol(b.c_str(), &end, 10);
  if (b.empty() || *end || first < 0 || last < first || last >= count)
    throw InputError(setting, "\"" + text + "\"", allowed);
  return {static_cast<int>(first), static_cast<int>(last) + 1};
}

}  // namespace skyspec
