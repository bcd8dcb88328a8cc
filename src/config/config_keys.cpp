#include "surface_nbv/config/config_keys.h"

#include <cmath>

namespace surface_nbv {

void readFlightKeys(ParamSource& m, MissionFlightConfig* c) {
  m.get("speed", &c->speed);
  m.get("yaw_rate", &c->yaw_rate);
  m.get("leg_lookahead", &c->leg_lookahead);
  m.get("leg_yaw_tolerance", &c->leg_yaw_tolerance);
  m.get("max_flight_time", &c->max_flight_time);
  m.get("start_spin", &c->start_spin);
}

void readTsdfKeys(ParamSource& nbv, TsdfConfig* c) {
  nbv.get("voxel_size", &c->voxel_size);
  nbv.get("w_th", &c->w_th);
  nbv.get("mesh_min_weight", &c->mesh_min_weight);
  nbv.get("truncation", &c->truncation);
  nbv.get("mesh_truncation", &c->mesh_truncation);
  nbv.get("mesh_voxel_size", &c->mesh_voxel_size);
  nbv.get("weight_dropoff", &c->weight_dropoff);
  nbv.get("mesh_weight_dropoff", &c->mesh_weight_dropoff);
  nbv.get("bounds_min", &c->bounds.min);
  nbv.get("bounds_max", &c->bounds.max);
}

void readCameraKeys(ParamSource& nbv, CameraConfig* c) {
  nbv.get("camera/width", &c->width);
  nbv.get("camera/height", &c->height);
  nbv.get("camera/hfov_deg", &c->hfov_deg);
  nbv.get("camera/vfov_deg", &c->vfov_deg);
  nbv.get("camera/min_range", &c->min_range);
  nbv.get("camera/max_range", &c->max_range);
  nbv.get("camera/rate_hz", &c->rate_hz);
  nbv.get("camera/noise_k", &c->noise_k);
  nbv.get("camera/noise_seed", &c->noise_seed);
  nbv.get("camera/pitch_deg", &c->pitch_deg);
  nbv.get("camera/noise_sigma0", &c->sensor.noise_sigma0);
  nbv.get("camera/noise_sigma1", &c->sensor.noise_sigma1);
  nbv.get("camera/lateral_noise_px", &c->sensor.lateral_noise_px);
  nbv.get("camera/grazing_dropout_deg", &c->sensor.grazing_dropout_deg);
  nbv.get("camera/dropout_rate", &c->sensor.dropout_rate);
  nbv.get("camera/dropout_patch_fraction", &c->sensor.dropout_patch_fraction);
  nbv.get("camera/dropout_patch_size", &c->sensor.dropout_patch_size);
  nbv.get("camera/dropout_patch_rate", &c->sensor.dropout_patch_rate);
  nbv.get("camera/quantization", &c->sensor.quantization);
}

void readSurfaceKeys(ParamSource& nbv, SurfaceConfig* c) {
  nbv.get("delta_pose", &c->delta_pose);
  nbv.get("d_nu", &c->d_nu);
  nbv.get("d_nu_max", &c->d_nu_max);
  nbv.get("approach_range_fraction", &c->approach_range_fraction);
}

void readUtilityKeys(ParamSource& nbv, ClusterGraphConfig* c) {
  nbv.get("lambda_tc", &c->lambda_tc);
  nbv.get("lambda_ic", &c->lambda_ic);
}

void readSceneKeys(ParamSource& sim, SceneConfig* c) {
  sim.get("scene", &c->scene);
  sim.get("scene_up_axis", &c->transform.up_axis);
  sim.get("scene_scale", &c->transform.scale);
  sim.get("scene_fit_size", &c->transform.fit_size);
  sim.get("scene_offset", &c->transform.offset);
  sim.get("crop_min", &c->transform.crop.min);
  sim.get("crop_max", &c->transform.crop.max);
}

void readTrackerKeys(ParamSource& trk, TrackerSimConfig* c) {
  trk.get("drag", &c->model.drag);
  trk.get("v_max", &c->model.v_max);
  trk.get("a_max", &c->model.a_max);
  trk.get("yaw_rate_max", &c->model.yaw_rate_max);
  trk.get("jerk_max", &c->mpc.jerk_max);
}

void readExplorerKeys(ParamSource& m, ExplorerConfig* e) {
  m.get("match_radius", &e->match_radius);
  m.get("reach_tolerance", &e->reach_tolerance);
  m.get("max_failures", &e->max_failures);
  m.get("max_visits", &e->max_visits);
  m.get("blacklist_radius", &e->blacklist_radius);
  m.get("always_full", &e->always_full);
  m.get("travel_yaw", &e->travel_yaw);
  m.get("turn_distance", &e->turn_distance);
  m.get("min_visible", &e->min_visible);
  m.get("head_lookahead", &e->head_lookahead);
  m.get("head_unknown", &e->head_unknown);
  m.get("head_lambda", &e->head_lambda);
  m.get("head_vertical_scale", &e->head_vertical_scale);
  m.get("gaze", &e->gaze.enabled);
  m.get("gaze_step", &e->gaze.step);
  m.get("gaze_min_ises", &e->gaze.min_ises);
  m.get("pool_unknown_below", &e->pool_unknown_below);
  m.get("path_distances", &e->path_distances);
  m.get("check_reachable", &e->check_reachable);
  m.get("corridor_guide", &e->corridor_guide);
  m.get("empty_updates_before_done", &e->empty_updates_before_done);
  m.get("max_leg_attempts", &e->max_leg_attempts);
  m.get("leg_time_budget", &e->leg_time_budget);
  std::string objective = toString(e->graph.objective);
  m.get("tour_objective", &objective);
  if (!parseTourObjective(objective, &e->graph.objective)) m.fail("tour_objective", "expected 'product' or 'sum'");
}

void readPathKeys(ParamSource& m, PathPlannerConfig* c) {
  m.get("path_time_budget", &c->time_budget);
  m.get("path_iterations", &c->iteration_budget);
  m.get("path_lattice_step", &c->lattice_step);
  uint64_t nodes = c->lattice_max_nodes;
  m.get("path_lattice_nodes", &nodes);
  c->lattice_max_nodes = static_cast<size_t>(nodes);
}

void readPoseErrorKeys(ParamSource& m, PoseErrorConfig* c) {
  m.get("pose_drift_rate", &c->drift_rate);
  m.get("pose_yaw_drift_deg", &c->yaw_drift_deg);
  m.get("pose_jitter", &c->jitter_position);
  m.get("pose_jitter_deg", &c->jitter_angle_deg);
  m.get("pose_error_seed", &c->seed);
}

void readInvalidPixelsKey(ParamSource& source, const std::string& key, TsdfConfig* c) {
  std::string policy = toString(c->invalid_pixels);
  source.get(key, &policy);
  if (!parseInvalidPixelPolicy(policy, &c->invalid_pixels)) {
    source.fail(key, "expected 'ignore', 'clear' or 'clear_inf', got '" + policy + "'");
  }
}

}  // namespace surface_nbv
