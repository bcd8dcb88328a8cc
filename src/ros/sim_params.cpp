#include "surface_nbv/ros/sim_params.h"

#include <cmath>

#include "surface_nbv/config/config_keys.h"

namespace surface_nbv {

Status DepthSimConfig::validate() const {
  if (Status s = scene.validate(); !s) return s;
  if (world_frame.empty()) return Status::Error("world_frame expected a frame name");
  if (camera_frame.empty() || camera_frame == world_frame) {
    return Status::Error("camera_frame expected a frame name different from world_frame");
  }
  if (render_threads < 1 || render_threads > 64) return Status::Error("render_threads expected in [1, 64]");
  if (points_stride < 1) return Status::Error("points_stride expected >= 1");
  if (!std::isfinite(tf_timeout) || tf_timeout < 0.0 || tf_timeout > 1.0) {
    return Status::Error("tf_timeout expected in [0, 1] s");
  }
  if (!std::isfinite(stats_period) || stats_period <= 0.0) return Status::Error("stats_period expected > 0");
  if (export_directory.empty()) return Status::Error("export_directory expected a directory");
  if (encoding != "32FC1" && encoding != "16UC1") return Status::Error("encoding expected '32FC1' or '16UC1'");
  if (Status s = pose_error.validate(); !s) return s;
  return Status::Ok();
}

Status loadDepthSimParams(const ros::NodeHandle& priv, CameraConfig* camera, DepthSimConfig* config) {
  ParamReader reader(priv);
  reader.get("shared_namespace", &config->shared_namespace);
  readSceneKeys(reader, &config->scene);
  reader.get("world_frame", &config->world_frame);
  reader.get("camera_frame", &config->camera_frame);
  reader.get("render_threads", &config->render_threads);
  reader.get("publish_points", &config->publish_points);
  reader.get("points_stride", &config->points_stride);
  reader.get("tf_timeout", &config->tf_timeout);
  reader.get("stats_period", &config->stats_period);
  reader.get("export_directory", &config->export_directory);
  reader.get("encoding", &config->encoding);
  // The odometry error of the mission section (nbv_mission's mission/pose_*
  // keys), unless the node's own ~pose_* are given.
  reader.get("mission_namespace", &config->mission_namespace);
  ParamReader mission((ros::NodeHandle(config->mission_namespace)));
  readPoseErrorKeys(mission, &config->pose_error);
  if (Status s = mission.status(); !s) return s;
  readPoseErrorKeys(reader, &config->pose_error);
  reader.checkUnknown();
  if (Status s = reader.status(); !s) return s;
  if (Status s = config->validate(); !s) return Status::Error(priv.getNamespace() + "/" + s.message());

  ParamReader shared_reader(ros::NodeHandle(config->shared_namespace));
  readCameraKeys(shared_reader, camera);
  shared_reader.checkUnknown("camera");
  if (Status s = shared_reader.status(); !s) return s;
  if (Status s = camera->validate(); !s) return Status::Error(shared_reader.ns() + "/" + s.message());
  return Status::Ok();
}

}  // namespace surface_nbv
