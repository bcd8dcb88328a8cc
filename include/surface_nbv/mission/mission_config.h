// Everything one headless mission needs (nbv_mission), read from the same
// YAML files the ROS launch loads (config/<scene>.yaml), so both run the same
// parameters:
//   nbv:        shared map, camera and Table 1 parameters (voxel_size, w_th,
//               bounds_min/max, camera{...}, delta_pose, d_nu, d_nu_max,
//               lambda_tc, lambda_ic)
//   depth_sim:  the scene (scene, scene_up_axis, scene_scale, scene_fit_size,
//               scene_offset, crop_min/max),
//               its other, node-only keys are not read here
//   mission:    the mission itself (start pose, speed, frame rate, frontier
//               period, budgets, seeds); every key optional, unknown keys refused.
// The same readers (config/config_keys.h) read these keys in the ROS nodes,
// so a file one refuses the other refuses. ROS-free (yaml-cpp). Units: metres, seconds, radians unless a key says _deg.
#pragma once

#include <set>
#include <string>

#include "surface_nbv/config/config_keys.h"
#include "surface_nbv/eval/eval_config.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/manhattan_yaw.h"
#include "surface_nbv/map/tsdf_config.h"
#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/planning/path_planner.h"
#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sim/pose_error.h"
#include "surface_nbv/sim/scene_source.h"
#include "surface_nbv/surface/surface_config.h"
#include "surface_nbv/tracking/tracker_sim.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// The mission section's flight keys (speed, yaw_rate, leg_lookahead,
// leg_yaw_tolerance, max_flight_time, start_spin) are MissionFlightConfig's, the
// same keys and checks as nbv_planner's (config_keys.h).
struct MissionConfig : MissionFlightConfig {
  MissionConfig() { max_flight_time = 5400.0; }  // 90 minutes of flight; 0: no limit

  SceneConfig scene;
  CameraConfig camera;
  TsdfConfig tsdf;
  CollisionConfig collision;
  SurfaceConfig surface;
  ExplorerConfig explorer;
  // Legs bounded by wall time (0.5 s) by default: fast, but a loaded machine
  // may plan differently. For exact repeats set mission/path_iterations
  // (roadmap samples per leg, e.g. 20000), as test_mission does.
  PathPlannerConfig path;
  // The simulated UAV (YAML section `tracker`: drag, v_max, a_max,
  // yaw_rate_max, jerk_max; the MPC's limits are the model's).
  TrackerSimConfig tracker;
  // The keys a config file or a command-line option gave ("nbv/voxel_size",
  // "nbv/camera/max_range", "mission/start", "depth_sim/scene_up_axis"):
  // deriveSceneDefaults (scene_defaults.h) derives only the others.
  std::set<std::string> given_keys;

  Eigen::Vector4d start{0.0, 0.0, 2.0, 0.0};  // [x, y, z, yaw] at take-off
  double frame_rate = 5.0;         // depth frames integrated per flight second
  double frontier_period = 4.0;    // flight seconds between frontier updates on a leg
  double max_path_length = 0.0;    // or when the flown path reaches this [m]; 0: no limit
  double start_free_radius = 3.0;  // the take-off ball is free space [m]
  double progress_period = 60.0;   // flight seconds between progress lines
  int threads = 2;                 // render, integration and frontier threads
  // Frames the mesh layer may lag behind the planning map (MeshLayer::
  // setQueueDepth): it catches up on the second core while the explorer
  // plans on one. 1 waits for every frame; 64 depth images at 640 x 480 are
  // 79 MB. The maps and the flight are the same either way.
  int mesh_layer_queue = 64;
  unsigned int seed = 1;           // path sampling and depth noise (per trial: seed + trial)
  // Odometry drift and jitter (pose_error.h; mission/pose_drift_rate,
  // pose_yaw_drift_deg, pose_jitter, pose_jitter_deg, pose_error_seed): the
  // UAV flies and maps on its estimate, the camera renders at the truth.
  // Off by default. Its seed is pose_error_seed + seed.
  PoseErrorConfig pose_error;
  // The heading from the walls' directions (manhattan_yaw.h,
  // mission/manhattan_yaw, manhattan_yaw_gain): for structures of walls 90
  // degrees apart. Off by default.
  ManhattanYawConfig manhattan_yaw;

  // Names the first bad key.
  Status validate() const;
  // The mission's rules as nbv_mission applies them (MissionRunner): a
  // decision every frontier_period, a leg ended when the tracker says so.
  SupervisorConfig supervisorConfig() const;
};

// Reads `file` over the defaults of *config. Error (naming file and key) on
// a missing file, bad YAML, a value of the wrong type or an unknown key of
// the mission section.
Status loadMissionConfig(const std::string& file, MissionConfig* config);
// The same from YAML text; `name` stands for the file in errors.
Status loadMissionConfigText(const std::string& text, const std::string& name, MissionConfig* config);

// The body of both: the four sections from any ParamSource (YAML sections
// here, ROS namespaces in ros/mission_params.h), with the tracker and mission
// sections' unknown keys refused. Errors name the source's key.
Status loadMissionConfigFrom(ParamSource& nbv, ParamSource& depth_sim, ParamSource& tracker, ParamSource& mission,
                             MissionConfig* config);

// The configuration for a built-in scene name or mesh file: config/<scene>.yaml
// of the package when it exists (`package_dir` is the package's source
// directory), else the defaults with the scene set.
std::string defaultConfigFile(const std::string& package_dir, const std::string& scene);

// The evaluation a mission's reconstruction is reported with (nbv_mission,
// nbv_refuse): e_max from the voxel size, the camera's depth range and the
// planner's collision radius for the visibility pruning.
EvalConfig missionEvalConfig(const MissionConfig& c);

}  // namespace surface_nbv
