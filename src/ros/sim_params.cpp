#include "surface_nbv/ros/sim_params.h"

#include <cmath>

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

void readCameraConfig(ParamReader* reader, CameraConfig* c) {
  reader->get("camera/width", &c->width);
  reader->get("camera/height", &c->height);
  reader->get("camera/hfov_deg", &c->hfov_deg);
  reader->get("camera/vfov_deg", &c->vfov_deg);
  reader->get("camera/min_range", &c->min_range);
  reader->get("camera/max_range", &c->max_range);
  reader->get("camera/rate_hz", &c->rate_hz);
  reader->get("camera/noise_k", &c->noise_k);
  reader->get("camera/noise_seed", &c->noise_seed);
  reader->get("camera/pitch_deg", &c->pitch_deg);
  reader->get("camera/noise_sigma0", &c->sensor.noise_sigma0);
  reader->get("camera/noise_sigma1", &c->sensor.noise_sigma1);
  reader->get("camera/lateral_noise_px", &c->sensor.lateral_noise_px);
  reader->get("camera/grazing_dropout_deg", &c->sensor.grazing_dropout_deg);
  reader->get("camera/dropout_rate", &c->sensor.dropout_rate);
  reader->get("camera/dropout_patch_fraction", &c->sensor.dropout_patch_fraction);
  reader->get("camera/dropout_patch_size", &c->sensor.dropout_patch_size);
  reader->get("camera/dropout_patch_rate", &c->sensor.dropout_patch_rate);
  reader->get("camera/quantization", &c->sensor.quantization);
}

void readSceneConfig(ParamReader* reader, SceneConfig* c) {
  reader->get("scene", &c->scene);
  reader->get("scene_up_axis", &c->transform.up_axis);
  reader->get("scene_scale", &c->transform.scale);
  reader->get("scene_fit_size", &c->transform.fit_size);
  reader->get("scene_offset", &c->transform.offset);
  reader->get("crop_min", &c->transform.crop.min);
  reader->get("crop_max", &c->transform.crop.max);
}

Status loadDepthSimParams(const ros::NodeHandle& priv, CameraConfig* camera, DepthSimConfig* config) {
  ParamReader reader(priv);
  reader.get("shared_namespace", &config->shared_namespace);
  readSceneConfig(&reader, &config->scene);
  reader.get("world_frame", &config->world_frame);
  reader.get("camera_frame", &config->camera_frame);
  reader.get("render_threads", &config->render_threads);
  reader.get("publish_points", &config->publish_points);
  reader.get("points_stride", &config->points_stride);
  reader.get("tf_timeout", &config->tf_timeout);
  reader.get("stats_period", &config->stats_period);
  reader.get("export_directory", &config->export_directory);
  reader.get("encoding", &config->encoding);
  reader.get("pose_drift_rate", &config->pose_error.drift_rate);
  reader.get("pose_yaw_drift_deg", &config->pose_error.yaw_drift_deg);
  reader.get("pose_jitter", &config->pose_error.jitter_position);
  reader.get("pose_jitter_deg", &config->pose_error.jitter_angle_deg);
  reader.get("pose_error_seed", &config->pose_error.seed);
  reader.checkUnknown();
  if (Status s = reader.status(); !s) return s;
  if (Status s = config->validate(); !s) return Status::Error(priv.getNamespace() + "/" + s.message());

  ParamReader shared_reader(ros::NodeHandle(config->shared_namespace));
  readCameraConfig(&shared_reader, camera);
  shared_reader.checkUnknown("camera");
  if (Status s = shared_reader.status(); !s) return s;
  if (Status s = camera->validate(); !s) return Status::Error(shared_reader.ns() + "/" + s.message());
  return Status::Ok();
}

}  // namespace surface_nbv
