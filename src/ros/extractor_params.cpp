#include "surface_nbv/ros/extractor_params.h"

#include <cmath>

#include "surface_nbv/mission/mission_config.h"
#include "surface_nbv/ros/mapper_params.h"
#include "surface_nbv/ros/sim_params.h"

namespace surface_nbv {

Status ExtractorConfig::validate() const {
  if (Status s = map.validate(); !s) return s;
  if (Status s = surface.validate(); !s) return s;
  if (Status s = collision.validate(); !s) return s;
  if (world_frame.empty()) return Status::Error("world_frame expected a frame name");
  if (!std::isfinite(frontier_period) || frontier_period < 0.0) {
    return Status::Error("frontier_period expected >= 0 s (0: rate per wall second)");
  }
  if (!std::isfinite(rate) || rate <= 0.0 || rate > 50.0) return Status::Error("rate expected in (0, 50] Hz");
  if (Status s = feed.validate(); !s) return s;
  if (!std::isfinite(stats_period) || stats_period <= 0.0) return Status::Error("stats_period expected > 0");
  return Status::Ok();
}

Status loadExtractorParams(const ros::NodeHandle& priv, ExtractorConfig* c) {
  ParamReader reader(priv);
  SurfaceConfig& s = c->surface;
  reader.get("shared_namespace", &c->shared_namespace);
  reader.get("fallback_rotations_deg", &s.fallback_rotations_deg);
  reader.get("fallback_distance_fractions", &s.fallback_distance_fractions);
  reader.get("fov_margin_deg", &s.fov_margin_deg);
  reader.get("unknown_blocks_visibility", &s.unknown_blocks_visibility);
  reader.get("d_nu_step", &s.d_nu_step);
  reader.get("threads", &s.threads);
  reader.get("collision_max_distance", &c->collision.max_distance);
  reader.get("collision_cell_size", &c->collision.min_cell_size);
  reader.get("world_frame", &c->world_frame);
  reader.get("mission_namespace", &c->mission_namespace);
  // The mission section's keys of this stage (nbv_mission's), then the node's own.
  // With a mission section the frontier period defaults to nbv_mission's.
  if (ros::param::has(c->mission_namespace)) c->frontier_period = MissionConfig().frontier_period;
  ParamReader mission((ros::NodeHandle(c->mission_namespace)));
  mission.get("frontier_period", &c->frontier_period);
  mission.get("collision_radius", &s.collision_radius);
  mission.get("epsilon", &s.epsilon);
  mission.get("parallel_distance", &s.parallel_distance);
  mission.get("parallel_cos", &s.parallel_cos);
  if (Status st = mission.status(); !st) return st;
  reader.get("frontier_period", &c->frontier_period);  // the node's own value wins
  reader.get("collision_radius", &s.collision_radius);
  reader.get("epsilon", &s.epsilon);
  reader.get("parallel_distance", &s.parallel_distance);
  reader.get("parallel_cos", &s.parallel_cos);
  reader.get("rate", &c->rate);
  readMapFeedKeys(&reader, &c->feed);
  reader.get("stats_period", &c->stats_period);
  reader.checkUnknown();
  if (Status st = reader.status(); !st) return st;

  ParamReader shared(ros::NodeHandle(c->shared_namespace));
  readTsdfKeys(shared, &c->map);
  readSurfaceKeys(shared, &s);
  readCameraKeys(shared, &s.camera);
  shared.checkUnknown("camera");
  if (Status st = shared.status(); !st) return st;
  if (Status st = s.camera.validate(); !st) return Status::Error(c->shared_namespace + "/" + st.message());
  if (Status st = c->validate(); !st) return Status::Error(priv.getNamespace() + "/" + st.message());
  return Status::Ok();
}

}  // namespace surface_nbv
