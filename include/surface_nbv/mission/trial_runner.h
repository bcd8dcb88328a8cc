// N seeded exploration trials of one scene, evaluated against its ground
// truth (nbv_mission's work, ROS-free): reads the config, derives the keys it
// leaves out from the scene (scene_defaults.h), flies every trial with a
// MissionRunner, evaluates its reconstruction and writes
//   DIR/trial_K/: reconstruction.ply, map.tsdf, path.csv (flown poses),
//                 events.csv (every frontier update), eval/ (the evaluation's
//                 report and clouds), coverage.csv (coverage_every) and the
//                 PNG plots (plots),
//   DIR/:         report.json and report.md over all trials (the paper's
//                 Table 2 columns, mean and standard deviation).
// What it prints goes to the `out` stream (the lines nbv_mission prints),
// warnings to `err`. An option or config that cannot run, a trial that fails
// or a file that cannot be written is an error Status (its message as
// nbv_mission prints it after "nbv_mission: "); nothing throws for a bad option.
#pragma once

#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "surface_nbv/mission/flight_profile.h"
#include "surface_nbv/mission/mission_runner.h"
#include "surface_nbv/mission/scene_defaults.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// nbv_mission's options; an unset optional leaves the config's value (or the
// default named). Errors name the options by their flags (--trials, ...).
struct TrialOptions {
  // The package's source directory: config/<scene>.yaml, the reference configs
  // of the derived keys and scripts/plot_mission.py.
  std::string package_dir;
  // --config: the YAML read over the defaults; unset: config/<scene>.yaml of
  // the package when it exists (scene "plant" when unset too); "": none.
  std::optional<std::string> config_file;
  // The scene options (--scene, --up-axis, --scale, --fit-size, --offset,
  // --crop-min, --crop-max) over the config's depth_sim section, each
  // recorded as given (depth_sim/scene, ...).
  std::optional<std::string> scene, up_axis;
  std::optional<double> scale;
  std::optional<Eigen::Vector3d> fit_size, offset, crop_min, crop_max;

  int trials = 1;  // 1..100, seeds seed .. seed + trials - 1
  int seed = 1;    // >= 0
  std::optional<std::string> out_dir;  // default output/mission_<scene stem>
  // Over the config's mission/threads, max_flight_time, max_path_length and
  // nbv/voxel_size (recorded as given: derived keys follow it).
  std::optional<int> threads;
  std::optional<double> max_flight_time, max_path_length, voxel_size;
  // Evaluates the reconstruction every S >= 1 s of flight and at the end.
  std::optional<double> coverage_every;
  // Diagnostic: ranks the tour's first N >= 2 viewpoints by the true surface
  // in their view (oracle_gain.h) times exp(-L d), L = oracle_lambda >= 0
  // (only with oracle_gain), else the config's lambda_tc.
  std::optional<int> oracle_gain;
  std::optional<double> oracle_lambda;
  // PNG plots per trial (scripts/plot_mission.py, when matplotlib is installed).
  bool plots = true;
};

// The evaluated coverage at one checkpoint of a trial (coverage_every).
struct CoveragePoint {
  double t = 0, path_length = 0, coverage = 0, rmse = 0;
};

// One trial's line of the report.
struct TrialRow {
  std::vector<CoveragePoint> coverage_over_time;
  int trial = 0;
  unsigned seed = 0;
  bool completed = false;
  std::string end_reason;
  double path_length = 0, flight_min = 0, coverage = 0, mean = 0, std_dev = 0, rmse = 0, wall_s = 0;
  double plan_ms_max = 0, frontier_ms_max = 0;
  MissionStageTimes times;
  PoseErrorStats pose_error, fused_pose_error;
  size_t yaw_corrections = 0;
  FlightProfile profile;
  size_t frames = 0, updates = 0, full = 0, local = 0, legs = 0, failures = 0, blacklisted = 0, final_inside = 0;
  size_t roadmap_growths = 0, roadmap_vertices = 0;  // the leg planner's (ExplorerStats)
  size_t lattice_legs = 0, corridor_legs = 0;         // legs found by the lattice, along the corridor
};

struct TrialResult {
  MissionConfig config;     // the trials' config (trial K flies seed options.seed + K)
  std::string config_file;  // the file read, "" when none
  std::string out_dir;
  SceneDefaults derived;    // the keys derived from the scene
  std::vector<TrialRow> rows;  // one per trial that ran

  // Every trial ended by itself (no ISE of C_ins left).
  bool allCompleted() const;
};

class TrialRunner {
 public:
  // `out` and `err` must outlive run(); `name` prefixes the warnings ("NAME: warning: ...").
  explicit TrialRunner(std::ostream& out = std::cout, std::ostream& err = std::cerr, std::string name = "nbv_mission");

  // Runs options.trials trials and writes their files and reports. On error
  // *result holds what ran before it.
  Status run(const TrialOptions& options, TrialResult* result) const;

 private:
  void warn(const std::string& message) const;

  std::ostream& out_;
  std::ostream& err_;
  std::string name_;
};

}  // namespace surface_nbv
