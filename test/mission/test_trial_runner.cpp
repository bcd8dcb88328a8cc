// TrialRunner (nbv_mission's trials, ROS-free): short trials on the built-in
// box write their files and reports; a bad option or config is an error
// Status that names it, before anything flies.
#include "surface_nbv/mission/trial_runner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include <yaml-cpp/yaml.h>

using namespace surface_nbv;
namespace fs = std::filesystem;

namespace {

std::string tempPath(const std::string& name) {
  const std::string path = ::testing::TempDir() + "/trial_runner_" + name;
  fs::remove_all(path);
  return path;
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

size_t lineCount(const std::string& path) {
  const std::string text = readText(path);
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

// The box with config/box.yaml, a short flight and no plots.
TrialOptions boxOptions(const std::string& out_dir) {
  TrialOptions o;
  o.package_dir = NBV_SOURCE_DIR;
  o.scene = "box";
  o.out_dir = out_dir;
  o.max_flight_time = 20.0;
  o.plots = false;
  return o;
}

struct TrialRun {
  Status status;
  TrialResult result;
  std::string out, err;
};

TrialRun runTrials(const TrialOptions& options) {
  TrialRun r;
  std::ostringstream out, err;
  EXPECT_NO_THROW(r.status = TrialRunner(out, err).run(options, &r.result));
  r.out = out.str();
  r.err = err.str();
  return r;
}

}  // namespace

TEST(TrialRunner, ShortBoxTrialsWriteTheirFilesAndReports) {
  const std::string dir = tempPath("box");
  TrialOptions o = boxOptions(dir);
  o.trials = 2;
  o.seed = 3;
  o.coverage_every = 10.0;
  const TrialRun r = runTrials(o);
  ASSERT_TRUE(r.status.ok()) << r.status.message() << "\n" << r.out << r.err;
  EXPECT_EQ(r.result.config_file, std::string(NBV_SOURCE_DIR) + "/config/box.yaml");
  EXPECT_EQ(r.result.out_dir, dir);
  EXPECT_DOUBLE_EQ(r.result.config.max_flight_time, 20.0);  // the option over the config's 900 s
  EXPECT_FALSE(r.result.derived.derivedAny());               // box.yaml gives every key

  // Stopped by the flight limit: not completed, but part of the box is covered.
  ASSERT_EQ(r.result.rows.size(), 2u);
  EXPECT_FALSE(r.result.allCompleted());
  for (int k = 0; k < 2; ++k) {
    const TrialRow& row = r.result.rows[k];
    EXPECT_EQ(row.trial, k);
    EXPECT_EQ(row.seed, 3u + k);
    EXPECT_FALSE(row.completed);
    EXPECT_NE(row.end_reason.find("max_flight_time"), std::string::npos) << row.end_reason;
    EXPECT_NEAR(row.flight_min, 20.0 / 60.0, 0.02);
    EXPECT_GT(row.coverage, 0.05);
    EXPECT_LE(row.coverage, 1.0);
    EXPECT_GT(row.frames, 50u);  // 5 frames a second
    ASSERT_GE(row.coverage_over_time.size(), 2u);  // at 10 s and at the end
    EXPECT_DOUBLE_EQ(row.coverage_over_time.back().coverage, row.coverage);

    const std::string trial = dir + "/trial_" + std::to_string(k);
    for (const char* file : {"path.csv", "events.csv", "map.tsdf", "reconstruction.ply", "coverage.csv",
                             "eval/report.json"}) {
      EXPECT_TRUE(fs::exists(trial + "/" + file)) << trial << "/" << file;
    }
    EXPECT_EQ(lineCount(trial + "/path.csv"), row.frames + 1);  // a header and a pose per frame
    EXPECT_EQ(lineCount(trial + "/coverage.csv"), row.coverage_over_time.size() + 1);
    // events.csv: a row per frontier update, the decision's message last and
    // quoted (empty while the UAV flies its tour).
    std::istringstream events(readText(trial + "/events.csv"));
    std::string line;
    ASSERT_TRUE(std::getline(events, line));
    EXPECT_EQ(line.substr(line.rfind(",x_m")), ",x_m,y_m,z_m,yaw_rad,leg_failures,message");
    size_t rows = 0;
    while (std::getline(events, line)) {
      ++rows;
      EXPECT_EQ(line.back(), '"') << line;
      EXPECT_EQ(std::count(line.begin(), line.end(), '"') % 2, 0) << line;
    }
    EXPECT_GT(rows, 2u);
    EXPECT_FALSE(fs::exists(trial + "/path_top.png"));  // no plots
  }

  // report.json: the run, the summary over the trials and each trial.
  const YAML::Node json = YAML::LoadFile(dir + "/report.json");
  for (const char* key : {"scene", "config", "trials", "seed", "voxel_size_m", "e_max_m", "threads",
                          "render_packet_rays", "voxel_loop", "size_class", "map_bytes_estimate", "scene_box_m",
                          "reference_config", "derived", "summary", "per_trial"}) {
    EXPECT_TRUE(json[key]) << key;
  }
  EXPECT_EQ(json["scene"].as<std::string>(), "box");
  EXPECT_EQ(json["trials"].as<int>(), 2);
  EXPECT_EQ(json["seed"].as<int>(), 3);
  for (const char* key : {"path_length", "completion_time", "coverage", "error_mean", "error_std", "rmse",
                          "wall_time"}) {
    EXPECT_TRUE(json["summary"][key]["mean"]) << key;
  }
  EXPECT_NEAR(json["summary"]["coverage"]["mean"].as<double>(),
              50.0 * (r.result.rows[0].coverage + r.result.rows[1].coverage), 1e-6);
  ASSERT_EQ(json["per_trial"].size(), 2u);
  const YAML::Node first = json["per_trial"][0];
  for (const char* key : {"trial", "seed", "completed", "end_reason", "path_length_m", "completion_min", "coverage",
                          "error_mean_m", "error_std_m", "rmse_m", "wall_s", "frames", "frontier_updates",
                          "stage_ms", "flight_profile", "coverage_over_time"}) {
    EXPECT_TRUE(first[key]) << key;
  }
  EXPECT_FALSE(first["pose_error"]);  // no odometry error configured
  EXPECT_GT(first["coverage"].as<double>(), 0.05);
  EXPECT_EQ(first["seed"].as<int>(), 3);
  EXPECT_FALSE(first["completed"].as<bool>());

  const std::string md = readText(dir + "/report.md");
  EXPECT_NE(md.find("# Mission on `box` (2 trial(s), seeds 3..4)"), std::string::npos) << md;
  EXPECT_NE(md.find("Coverage over flight time"), std::string::npos) << md;

  // What nbv_mission prints: the scene, each trial, the summary.
  EXPECT_EQ(r.out.rfind("scene 'box': 12 triangles, 96 m^2", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("trial 0 (seed 3)\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("trial 1 (seed 4)\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  coverage at   0.2 min"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("summary over 2 trial(s):\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wrote " + dir + "/report.json and report.md"), std::string::npos) << r.out;
  // config/box.yaml's take-off ball reaches the box: a warning, not an error.
  EXPECT_NE(r.err.find("nbv_mission: warning: the take-off ball"), std::string::npos) << r.err;
}

TEST(TrialRunner, DerivesWhatNoConfigGives) {
  const std::string dir = tempPath("no_config");
  TrialOptions o = boxOptions(dir);
  o.config_file = "";  // none: every key from the scene
  o.max_flight_time = 5.0;
  o.voxel_size = 0.2;  // given: not derived
  const TrialRun r = runTrials(o);
  ASSERT_TRUE(r.status.ok()) << r.status.message() << "\n" << r.out << r.err;
  EXPECT_EQ(r.result.config_file, "");
  EXPECT_EQ(r.result.derived.size_class, "small");
  EXPECT_TRUE(r.result.derived.derivedAny());
  EXPECT_DOUBLE_EQ(r.result.config.tsdf.voxel_size, 0.2);
  EXPECT_NE(r.out.find("config (none); voxel 0.20 m"), std::string::npos) << r.out;
  const YAML::Node json = YAML::LoadFile(dir + "/report.json");
  EXPECT_TRUE(json["derived"]["mission/start"]);
  EXPECT_FALSE(json["derived"]["nbv/voxel_size"]);
  ASSERT_EQ(r.result.rows.size(), 1u);
  EXPECT_GT(r.result.rows[0].coverage, 0.0);
}

TEST(TrialRunner, BadOptionsAreErrorsNamingThem) {
  struct Case {
    const char* what;
    std::function<void(TrialOptions*)> set;
    const char* message;  // the error contains it
  };
  const std::string bad_key = tempPath("bad_key.yaml");
  std::ofstream(bad_key) << "mission:\n  max_flight_tme: 10\n";
  const std::string bad_value = tempPath("bad_value.yaml");
  std::ofstream(bad_value) << "nbv:\n  voxel_size: -1\n";
  const std::string bad_yaml = tempPath("bad_yaml.yaml");
  std::ofstream(bad_yaml) << "mission: [unclosed\n";
  const Case cases[] = {
      {"missing scene file", [](TrialOptions* o) { o->scene = "/nonexistent/scene.obj"; },
       "mesh file '/nonexistent/scene.obj' does not exist"},
      {"unknown config key", [&](TrialOptions* o) { o->config_file = bad_key; }, "max_flight_tme"},
      {"bad config value", [&](TrialOptions* o) { o->config_file = bad_value; }, "voxel_size expected > 0"},
      {"bad YAML", [&](TrialOptions* o) { o->config_file = bad_yaml; }, "cannot read"},
      {"missing config file", [](TrialOptions* o) { o->config_file = "/nonexistent/config.yaml"; }, "cannot read"},
      {"no trials", [](TrialOptions* o) { o->trials = 0; }, "--trials expects 1..100"},
      {"negative seed", [](TrialOptions* o) { o->seed = -1; }, "--seed >= 0"},
      {"coverage too often", [](TrialOptions* o) { o->coverage_every = 0.5; }, "--coverage-every expects >= 1 s"},
      {"lambda alone", [](TrialOptions* o) { o->oracle_lambda = 1.0; }, "--oracle-lambda goes with --oracle-gain"},
      {"one viewpoint", [](TrialOptions* o) { o->oracle_gain = 1; }, "--oracle-gain expects N >= 2"},
      {"negative lambda",
       [](TrialOptions* o) {
         o->oracle_gain = 3;
         o->oracle_lambda = -1.0;
       },
       "--oracle-lambda expects L >= 0"},
      {"bad scale", [](TrialOptions* o) { o->scale = -2.0; }, "scale"},
      {"bad threads", [](TrialOptions* o) { o->threads = 0; }, "mission/threads expected in [1, 64]"},
      {"out is a file",
       [&](TrialOptions* o) {
         std::ofstream(bad_key + ".file") << "x";
         o->out_dir = bad_key + ".file/out";
       },
       "cannot create"},
  };
  for (const Case& c : cases) {
    const std::string dir = tempPath("bad");
    TrialOptions o = boxOptions(dir);
    c.set(&o);
    const TrialRun r = runTrials(o);
    EXPECT_FALSE(r.status.ok()) << c.what;
    EXPECT_NE(r.status.message().find(c.message), std::string::npos) << c.what << ": " << r.status.message();
    EXPECT_TRUE(r.result.rows.empty()) << c.what;  // nothing flew
    EXPECT_EQ(r.out.find("trial 0"), std::string::npos) << c.what << ": " << r.out;
  }
  // A config error names its file, and stops before the output directory is made.
  const std::string dir = tempPath("bad_key_out");
  TrialOptions o = boxOptions(dir);
  o.config_file = bad_key;
  const TrialRun r = runTrials(o);
  EXPECT_EQ(r.status.message().rfind(bad_key + ": ", 0), 0u) << r.status.message();
  EXPECT_FALSE(fs::exists(dir));
}
