// Parameters of the simulator nodes: the camera model lives in the shared
// namespace (so mapper and planner read the same one), the scene and the
// node's own settings under its private namespace.
#pragma once

#include <string>

#include "surface_nbv/config/config_keys.h"
#include "surface_nbv/ros/param_reader.h"
#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sim/pose_error.h"
#include "surface_nbv/sim/scene_source.h"

namespace surface_nbv {

// The depth_sim node's own settings.
struct DepthSimConfig {
  SceneConfig scene;
  std::string shared_namespace = kSharedNamespace;  // where camera/* lives
  std::string mission_namespace = "/mission";        // where pose_* lives (then ~pose_*)
  std::string world_frame = "world";
  std::string camera_frame = "camera";
  int render_threads = 2;
  bool publish_points = false;
  int points_stride = 2;         // every n-th row and column in depth/points
  double tf_timeout = 0.05;      // s to wait for world -> camera at the frame time
  double stats_period = 1.0;     // s between ~stats messages
  // The only place ~export_scene writes: created at start-up if missing; the
  // service takes a plain file name inside it.
  std::string export_directory = "/tmp/surface_nbv_scenes";
  // "32FC1" (metres, REP 117) or "16UC1" (millimetres, 0 for no depth:
  // +Inf no-returns are lost, as with a real 16-bit driver).
  std::string encoding = "32FC1";
  // The odometry's error (pose_error.h; ~pose_drift_rate,
  // ~pose_yaw_drift_deg, ~pose_jitter, ~pose_jitter_deg, ~pose_error_seed):
  // TF carries the estimate, which the mapper fuses at; the depth is
  // rendered where the camera truly is. Off by default.
  PoseErrorConfig pose_error;

  Status validate() const;
};

// The keys (camera/*, scene*, pose_*) are read by config_keys.h, as nbv_mission reads them.
// Loads and validates everything depth_sim needs: the node's private keys
// from `priv` (unknown ones are errors), then camera/* from the shared
// namespace that `~shared_namespace` names.
Status loadDepthSimParams(const ros::NodeHandle& priv, CameraConfig* camera, DepthSimConfig* config);

}  // namespace surface_nbv
