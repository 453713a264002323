// Job files and their tasks (src/job/job_spec.hpp, job_plan.hpp): what the file may say and how
// errors name its keys; how sites x parameter sets x frames expand, in which order; that the random
// design depends on the seed alone; that shards and chunks cover every task exactly once; that the
// sun filter keeps exactly the frames with the sun high enough.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <set>
#include <string>

#include "check_helpers.hpp"
#include "job/job_plan.hpp"
#include "job/job_spec.hpp"
#include "physics/solar_position.hpp"
#include "scene_fixtures.hpp"
#include "skyspec/error.hpp"

BOOST_AUTO_TEST_SUITE(test_job_plan)

using namespace skyspec;

namespace {

JobSpec parse(const std::string& toml) { return parse_job(toml, "job.toml", std::filesystem::temp_directory_path()); }

template <class F>
std::string error_of(F f) {
  return test::input_error_message(f);
}
using test::contains;

const char* kTwoSites = R"(
[job]
name = "t"
produce = ["exr"]
[scene]
camera.width = 8
camera.height = 8
[[time]]
start = 2026-06-21T04:00:00+02:00
end = 2026-06-21T22:00:00+02:00
step_minutes = 60
[[site]]
name = "munich"
latitude_deg = 48.14
longitude_deg = 11.58
altitude_m = 520
[[site]]
name = "quito"
latitude_deg = -0.18
longitude_deg = -78.47
[axes]
"atmosphere.mie.scattering_per_m" = [1e-5, 4e-5]
"ground.albedo" = { start = 0.1, stop = 0.3, count = 3 }
)";

}  // namespace

BOOST_AUTO_TEST_CASE(expands_sites_then_parameters_then_frames) {
  const JobPlan plan = plan_job(parse(kTwoSites));
  // 19 hourly frames, 2 x 3 parameter sets, 2 sites.
  BOOST_TEST(plan.combinations.size() == 6u);
  BOOST_TEST(plan.tasks.size() == 2u * 6u * 19u);
  for (std::size_t k = 0; k < plan.tasks.size(); ++k) {
    const JobTask& t = plan.tasks[k];
    BOOST_TEST(t.index == static_cast<int>(k));
    BOOST_TEST(t.site == static_cast<int>(k / (6 * 19)));
    BOOST_TEST(t.combination == static_cast<int>(k / 19 % 6));
  }
  BOOST_TEST(plan.tasks[0].id() == "t000000");
  BOOST_TEST(plan.tasks[227].id() == "t000227");
  // The first axis varies slowest; ranges include both ends.
  BOOST_TEST(plan.combinations[0][0].second == "1.0000000000000001e-05");
  BOOST_TEST(plan.combinations[0][1].second == "0.10000000000000001");
  BOOST_TEST(plan.combinations[2][1].second == "0.29999999999999999");
  BOOST_TEST(plan.combinations[3][0].second == "4.0000000000000003e-05");
}

BOOST_AUTO_TEST_CASE(task_scene_has_the_site_time_and_parameters) {
  const JobPlan plan = plan_job(parse(kTwoSites));
  const JobTask& t = plan.tasks[6 * 19 + 19 + 5];  // quito, mie 1e-5 albedo 0.2, 09:00
  const Scene s = task_scene(plan, t);
  BOOST_TEST(s.location.latitude_deg == -0.18);
  BOOST_TEST(s.location.longitude_deg == -78.47);
  BOOST_TEST(s.sun.date_time == "2026-06-21T09:00:00+02:00");
  BOOST_TEST(s.atmosphere.mie.scattering_per_m == 1e-5);
  BOOST_TEST(s.atmosphere.ground.albedo == 0.2, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.output.name == "t000138");
  BOOST_TEST(s.output.directory == (plan.job.output_directory / "tasks").string());
  BOOST_TEST(s.output.exr);
  BOOST_TEST(!s.output.png);
  // A site's altitude raises the camera by as much (the preset's camera is 1 m up).
  BOOST_TEST(task_scene(plan, plan.tasks[0]).camera.position_m.z() == 521.0);
  BOOST_TEST(s.camera.position_m.z() == 1.0);
  // The sun of the task is the one the plan filtered on.
  BOOST_TEST(s.sun.elevation_deg == t.sun_elevation_deg, boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(sun_filter_keeps_exactly_the_frames_with_the_sun_high_enough) {
  JobSpec spec = parse(kTwoSites);
  spec.min_sun_elevation_deg = 10.0;
  const JobPlan plan = plan_job(spec);
  std::set<std::string> kept;
  for (const auto& t : plan.tasks) {
    BOOST_TEST(t.sun_elevation_deg >= 10.0);
    if (t.combination == 0) kept.insert(plan.site_name(t) + to_iso8601(*t.time));
  }
  // Every frame left out has the sun below 10 degrees (checked with the SPA directly).
  int left_out = 0;
  for (const auto& site : spec.sites)
    for (int h = 4; h <= 22; ++h) {
      DateTime when = spec.times[0].start;
      when = add_seconds(when, (h - 4) * 3600.0);
      if (kept.count(site.name + to_iso8601(when))) continue;
      ++left_out;
      const double el =
          solar_position(when, Observer{site.latitude_deg, site.longitude_deg, site.altitude_m + 1.0}).elevation_deg;
      BOOST_TEST(el < 10.0);
    }
  BOOST_TEST(left_out > 0);
  BOOST_TEST(plan.tasks.size() == (2u * 19u - static_cast<unsigned>(left_out)) * 6u);
}

BOOST_AUTO_TEST_CASE(random_design_depends_on_the_seed_alone) {
  const std::string job = R"(
[random]
seed = 42
samples = 50
[random.axes]
"atmosphere.ozone.column_DU" = { min = 250.0, max = 350.0 }
"render.view_segments" = { min = 8, max = 12 }
)";
  const JobPlan a = plan_job(parse(job)), b = plan_job(parse(job));
  BOOST_TEST(a.tasks.size() == 50u);
  std::set<std::string> distinct, whole;
  for (std::size_t k = 0; k < a.combinations.size(); ++k) {
    BOOST_TEST((a.combinations[k] == b.combinations[k]));
    const double oz = std::stod(a.combinations[k][0].second);
    BOOST_TEST((oz >= 250.0 && oz <= 350.0));
    distinct.insert(a.combinations[k][0].second);
    whole.insert(a.combinations[k][1].second);
  }
  BOOST_TEST(distinct.size() == 50u);
  // Whole numbers for an integer range, every value of 8..12 drawn in 50 samples.
  BOOST_TEST((whole == std::set<std::string>{"8", "9", "10", "11", "12"}));
  // Another seed, another design; adding an axis leaves the other axes' values as they were.
  std::string other = job;
  other.replace(other.find("seed = 42"), 9, "seed = 43");
  BOOST_TEST((plan_job(parse(other)).combinations[0] != a.combinations[0]));
  const JobPlan more = plan_job(parse(job + "\"ground.albedo\" = { min = 0.0, max = 0.5 }\n"));
  BOOST_TEST((more.combinations[7][0] == a.combinations[7][0]));
}

BOOST_AUTO_TEST_CASE(shards_and_chunks_cover_every_task_once) {
  const JobPlan plan = plan_job(parse(kTwoSites));
  const int total = static_cast<int>(plan.tasks.size());
  for (int n : {1, 2, 3, 7, 64, total, total + 5}) {
    int next = 0;
    for (int i = 1; i <= n; ++i) {
      const TaskRange r = plan.shard(i, n);
      BOOST_TEST(r.first == next);  // contiguous, in order, no gap, no overlap
      BOOST_TEST(r.size() >= total / n);
      BOOST_TEST(r.size() <= total / n + 1);
      next = r.last;
    }
    BOOST_TEST(next == total);
  }
  int next = 0;
  for (int k = 0; k < plan.chunk_count(); ++k) {
    BOOST_TEST(plan.chunk(k).first == next);
    BOOST_TEST(plan.chunk(k).size() <= plan.job.tasks_per_chunk);
    next = plan.chunk(k).last;
  }
  BOOST_TEST(next == total);
}

BOOST_AUTO_TEST_CASE(shard_and_task_range_syntax) {
  BOOST_TEST((parse_shard("3/8", "--shard") == std::pair<int, int>{3, 8}));
  for (const char* bad : {"0/4", "5/4", "1/0", "1", "a/b", "1/4x", "/4", "-1/4"})
    BOOST_TEST(contains(error_of([&] { parse_shard(bad, "--shard"); }), "--shard"), bad);
  BOOST_TEST(parse_task_range("4-9", 10, "--tasks").first == 4);
  BOOST_TEST(parse_task_range("4-9", 10, "--tasks").last == 10);
  BOOST_TEST(parse_task_range("7", 10, "--tasks").size() == 1);
  for (const char* bad : {"4-10", "5-4", "-1", "x", "", "3-"})
    BOOST_TEST(contains(error_of([&] { parse_task_range(bad, 10, "--tasks"); }), "--tasks"), bad);
}

BOOST_AUTO_TEST_CASE(errors_name_the_key_where_it_is_and_what_is_allowed) {
  const auto err = [](const std::string& toml) { return error_of([&] { plan_job(parse(toml)); }); };
  std::string e = err("[job]\nnmae = \"x\"\n");
  BOOST_TEST(contains(e, "job.nmae"));
  BOOST_TEST(contains(e, "job.toml:2:"));
  e = err("[[site]]\nname = \"a\"\nlatitude_deg = 95\nlongitude_deg = 0\n");
  BOOST_TEST(contains(e, "site[0].latitude_deg"));
  BOOST_TEST(contains(e, "-90 to 90"));
  e = err("[[site]]\nname = \"a b\"\nlatitude_deg = 5\nlongitude_deg = 0\n");
  BOOST_TEST(contains(e, "site[0].name"));
  e = err("[[time]]\nstart = 2026-06-21T04:00:00\nend = 2026-06-21T05:00:00+02:00\nstep_minutes = 5\n");
  BOOST_TEST(contains(e, "time[0].start"));
  BOOST_TEST(contains(e, "offset"));
  e = err("[[time]]\nstart = 2026-06-21T04:00:00Z\nend = 2026-06-20T05:00:00Z\nstep_minutes = 5\n");
  BOOST_TEST(contains(e, "time[0].end"));
  e = err("[[time]]\nstart = 2026-06-21T04:00:00Z\nend = 2026-06-22T05:00:00Z\n");
  BOOST_TEST(contains(e, "time[0].step_minutes"));
  e = err("[axes]\n\"ground.albedo\" = [0.1, 1.5]\n");  // the scene loader's own check, named by the axis
  BOOST_TEST(contains(e, "ground.albedo"));
  BOOST_TEST(contains(e, "axes.ground.albedo"));
  e = err("[axes]\n\"ground.albedoo\" = [0.1]\n");
  BOOST_TEST(contains(e, "ground.albedoo"));
  e = err("[axes]\n\"output.name\" = [\"a\"]\n");  // keys the job sets itself
  BOOST_TEST(contains(e, "axes.output.name"));
  e = err("[scene]\nsun.date_time = \"2026-06-21T04:00:00Z\"\n");
  BOOST_TEST(contains(e, "scene.sun.date_time"));
  e = err("[scene]\ncamera.width = -3\n");
  BOOST_TEST(contains(e, "camera.width"));
  e = err("[job]\nproduce = [\"exr\", \"tiff\"]\n");
  BOOST_TEST(contains(e, "job.produce"));
  e = err("[job]\nscene = \"no-such-scene.toml\"\n");
  BOOST_TEST(contains(e, "job.scene"));
  e = err("[job]\nscene = \"seed\"\nproduce = [\"irradiance\"]\n");  // the seed preset is RGB-fast
  BOOST_TEST(contains(e, "job.produce"));
  e = err("[random]\nsamples = 3\n[random.axes]\n\"ground.albedo\" = { min = 0.5, max = 0.1 }\n");
  BOOST_TEST(contains(e, "random.axes.ground.albedo.max"));
  e =
      err("[axes]\n\"ground.albedo\" = [0.1]\n[random]\nsamples = 3\n[random.axes]\n\"ground.albedo\" = { min = 0.0, "
          "max = 0.1 }\n");
  BOOST_TEST(contains(e, "not both"));
  e =
      err("[job]\nmin_sun_elevation_deg = 80\n[[time]]\nstart = 2026-12-21T12:00:00+01:00\n[[site]]\nname = \"oslo\"\n"
          "latitude_deg = 59.9\nlongitude_deg = 10.7\n");
  BOOST_TEST(contains(e, "job.min_sun_elevation_deg"));
  e = err("[[time]]\nstart = 2026-01-01T00:00:00Z\nend = 2026-12-31T00:00:00Z\nstep_minutes = 0.1\n");
  BOOST_TEST(contains(e, "step_minutes"));
  BOOST_TEST(contains(e, "at most"));
  BOOST_TEST(contains(err("[job\n"), "valid TOML"));
}

BOOST_AUTO_TEST_CASE(tiled_frames_are_strips_that_cover_the_image_once) {
  const JobPlan plan =
      plan_job(parse("[job]\ntile_rows = 300\n[scene]\ncamera.width = 128\ncamera.height = 1000\n"
                     "[axes]\n\"camera.height\" = [1000, 600]\n"));
  BOOST_TEST(plan.job.exr);
  BOOST_TEST(!plan.job.png);  // a tiled job produces the EXR alone unless it says otherwise
  BOOST_TEST(plan.frame_tasks.size() == 2u);
  BOOST_TEST(plan.frame_tasks[0].size() == 4);  // 300 + 300 + 300 + 100 rows
  BOOST_TEST(plan.frame_tasks[1].size() == 2);  // the second parameter set's image is 600 rows
  for (const auto& range : plan.frame_tasks) {
    int next = 0;
    for (int k = range.first; k < range.last; ++k) {
      const JobTask& t = plan.tasks[k];
      BOOST_REQUIRE(t.tile.has_value());
      BOOST_TEST(t.frame == static_cast<int>(&range - &plan.frame_tasks[0]));
      BOOST_TEST(t.tile->y0 == next);
      BOOST_TEST((t.tile->x0 == 0 && t.tile->x1 == 128));
      next = t.tile->y1;
    }
    BOOST_TEST(next == (range.first == 0 ? 1000 : 600));
  }
  BOOST_TEST(
      contains(error_of([] { parse("[job]\ntile_rows = 300\nproduce = [\"exr\", \"png\"]\n"); }), "job.tile_rows"));
}

BOOST_AUTO_TEST_CASE(a_job_without_sweeps_is_one_task_of_the_scene) {
  const JobPlan plan = plan_job(parse("[job]\nname = \"one\"\n"));
  BOOST_TEST(plan.tasks.size() == 1u);
  BOOST_TEST(plan.site_name(plan.tasks[0]) == "scene");
  BOOST_TEST(plan.job.output_directory.filename() == "one");
  BOOST_TEST(task_scene(plan, plan.tasks[0]).sun.elevation_deg == SceneLoader("default").finish().sun.elevation_deg);
}

BOOST_AUTO_TEST_SUITE_END()
