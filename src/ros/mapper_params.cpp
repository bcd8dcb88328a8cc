#include "surface_nbv/ros/mapper_params.h"

#include <cmath>
#include <limits>

#include <ros/param.h>

#include "surface_nbv/mission/mission_config.h"
#include "surface_nbv/ros/sim_params.h"

namespace surface_nbv {

Status MapperConfig::validate() const {
  if (Status s = tsdf.validate(); !s) return s;
  if (world_frame.empty()) return Status::Error("world_frame expected a frame name");
  if (input != "image" && input != "points") return Status::Error("input expected 'image' or 'points', got '" + input + "'");
  if (!std::isfinite(update_rate) || update_rate <= 0.0 || update_rate > 100.0) {
    return Status::Error("update_rate expected in (0, 100] Hz");
  }
  if (!std::isfinite(mesh_rate) || mesh_rate < 0.0 || mesh_rate > 100.0) return Status::Error("mesh_rate expected in [0, 100] Hz");
  if (!std::isfinite(stats_period) || stats_period <= 0.0) return Status::Error("stats_period expected > 0");
  if (map_directory.empty()) return Status::Error("map_directory expected a directory");
  if (max_pending_frames < 1 || max_pending_frames > 1000) return Status::Error("max_pending_frames expected in [1, 1000]");
  if (input_queue < 1 || input_queue > 1000) return Status::Error("input_queue expected in [1, 1000]");
  if (!std::isfinite(tf_wait) || tf_wait < 0.0 || tf_wait > 10.0) return Status::Error("tf_wait expected in [0, 10] s");
  if (!(autosave_period >= 0.0) || !std::isfinite(autosave_period)) return Status::Error("autosave_period expected >= 0 s");
  if (!(start_free_radius >= 0.0) || start_free_radius > 10.0) {
    return Status::Error("start_free_radius expected in [0, 10] m");
  }
  return Status::Ok();
}

Status loadSharedMapConfig(const std::string& ns, TsdfConfig* map) {
  ParamReader shared{ros::NodeHandle(ns)};
  readTsdfKeys(shared, map);
  return shared.status();
}

Status loadMapperParams(const ros::NodeHandle& priv, MapperConfig* c) {
  ParamReader reader(priv);
  reader.get("shared_namespace", &c->shared_namespace);
  reader.get("mission_namespace", &c->mission_namespace);
  // ~truncation overrides the shared nbv/truncation (read below).
  double truncation = std::numeric_limits<double>::quiet_NaN();
  reader.get("truncation", &truncation);
  double max_weight = c->tsdf.max_weight;
  reader.get("max_weight", &max_weight);
  c->tsdf.max_weight = static_cast<float>(max_weight);
  int max_blocks = static_cast<int>(c->tsdf.max_blocks);
  reader.get("max_blocks", &max_blocks);
  c->tsdf.max_blocks = max_blocks > 0 ? static_cast<size_t>(max_blocks) : 0;
  // The mission section's invalid_pixels and start_free_radius (nbv_mission's
  // keys), unless the node's own are given.
  // With a mission section the take-off ball defaults to nbv_mission's.
  if (ros::param::has(c->mission_namespace)) c->start_free_radius = MissionConfig().start_free_radius;
  ParamReader mission((ros::NodeHandle(c->mission_namespace)));
  readInvalidPixelsKey(mission, "invalid_pixels", &c->tsdf);
  mission.get("start_free_radius", &c->start_free_radius);
  if (Status s = mission.status(); !s) return s;
  readInvalidPixelsKey(reader, "invalid_pixels", &c->tsdf);
  reader.get("threads", &c->tsdf.threads);
  reader.get("world_frame", &c->world_frame);
  reader.get("input", &c->input);
  reader.get("update_rate", &c->update_rate);
  reader.get("mesh_rate", &c->mesh_rate);
  reader.get("stats_period", &c->stats_period);
  reader.get("map_directory", &c->map_directory);
  reader.get("max_pending_frames", &c->max_pending_frames);
  reader.get("input_queue", &c->input_queue);
  reader.get("tf_wait", &c->tf_wait);
  reader.get("start_free_radius", &c->start_free_radius);
  reader.get("autosave_period", &c->autosave_period);
  reader.get("resume", &c->resume);
  reader.checkUnknown();
  if (Status s = reader.status(); !s) return s;

  ParamReader shared(ros::NodeHandle(c->shared_namespace));
  readTsdfKeys(shared, &c->tsdf);
  if (priv.hasParam("truncation")) c->tsdf.truncation = truncation;
  readCameraKeys(shared, &c->camera);
  shared.checkUnknown("camera");
  if (Status s = shared.status(); !s) return s;
  if (Status s = c->camera.validate(); !s) return Status::Error(c->shared_namespace + "/" + s.message());
  if (Status s = c->validate(); !s) return Status::Error(priv.getNamespace() + "/" + s.message());
  return Status::Ok();
}

}  // namespace surface_nbv
