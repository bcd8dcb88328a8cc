// The config keys, one reader per struct, for both sides: the YAML sections
// nbv_mission reads (config/yaml_param_source.h) and the ROS namespaces the
// launch loads the same file into (ros/param_reader.h). A reader only reads
// (a wrong type or an unknown enum name is an error of the source); every
// range check is in the struct's validate(). Key names are the YAML's:
//   nbv/        readTsdfKeys, readCameraKeys ("camera/..."), readSurfaceKeys,
//               readUtilityKeys
//   depth_sim/  readSceneKeys
//   tracker/    readTrackerKeys
//   mission/    readFlightKeys, readExplorerKeys, readPathKeys,
//               readPoseErrorKeys, readInvalidPixelsKey
// ROS-free.
#pragma once

#include <string>

#include "surface_nbv/map/tsdf_config.h"
#include "surface_nbv/planning/cluster_graph.h"
#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/planning/mission_supervisor.h"
#include "surface_nbv/planning/path_planner.h"
#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sim/pose_error.h"
#include "surface_nbv/sim/scene_source.h"
#include "surface_nbv/surface/surface_config.h"
#include "surface_nbv/tracking/tracker_sim.h"
#include "surface_nbv/util/param_source.h"

namespace surface_nbv {

// MissionFlightConfig (the mission section's flight keys) is the
// supervisor's (planning/mission_supervisor.h).
void readFlightKeys(ParamSource& mission, MissionFlightConfig* c);
void readTsdfKeys(ParamSource& nbv, TsdfConfig* c);
void readCameraKeys(ParamSource& nbv, CameraConfig* c);
// delta_pose, d_nu, d_nu_max, approach_range_fraction.
void readSurfaceKeys(ParamSource& nbv, SurfaceConfig* c);
// lambda_tc, lambda_ic (eq. 5).
void readUtilityKeys(ParamSource& nbv, ClusterGraphConfig* c);
void readSceneKeys(ParamSource& depth_sim, SceneConfig* c);
// drag, v_max, a_max, yaw_rate_max (the model's, which the MPC plans with), jerk_max (the MPC's).
void readTrackerKeys(ParamSource& tracker, TrackerSimConfig* c);
// The explorer's keys (match_radius ... tour_objective, gaze, gaze_step, gaze_min_ises).
void readExplorerKeys(ParamSource& mission, ExplorerConfig* c);
// path_time_budget, path_iterations, path_lattice_step, path_lattice_nodes.
void readPathKeys(ParamSource& mission, PathPlannerConfig* c);
// pose_drift_rate, pose_yaw_drift_deg, pose_jitter, pose_jitter_deg, pose_error_seed.
void readPoseErrorKeys(ParamSource& mission, PoseErrorConfig* c);
// `key` ("invalid_pixels"): 'ignore', 'clear' or 'clear_inf'.
void readInvalidPixelsKey(ParamSource& source, const std::string& key, TsdfConfig* c);

}  // namespace surface_nbv
