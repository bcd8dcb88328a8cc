#include "surface_nbv/mission/mission_config.h"

#include <cmath>
#include <filesystem>
#include <set>

#include <yaml-cpp/yaml.h>

#include "surface_nbv/config/yaml_param_source.h"

namespace surface_nbv {

// The body of loadMissionConfig on a parsed document; `file` names it in errors.
Status loadMissionConfigNode(const YAML::Node& root, const std::string& file, MissionConfig* c);

SupervisorConfig MissionConfig::supervisorConfig() const {
  SupervisorConfig rules;
  rules.flight = *this;
  rules.reach_tolerance = explorer.reach_tolerance;
  rules.frontier_period = frontier_period;
  rules.leg_settle = -1.0;
  rules.max_path_length = max_path_length;
  return rules;
}

Status MissionConfig::validate() const {
  if (Status s = scene.validate(); !s) return s;
  if (Status s = camera.validate(); !s) return s;
  if (Status s = tsdf.validate(); !s) return s;
  if (Status s = collision.validate(); !s) return s;
  if (Status s = surface.validate(); !s) return s;
  if (Status s = explorer.validate(); !s) return s;
  if (Status s = path.validate(); !s) return s;
  if (Status s = tracker.validate(); !s) return s;
  if (!start.allFinite() || !tsdf.bounds.contains(start.head<3>())) {
    return Status::Error("mission/start expected a finite pose inside the map bounds");
  }
  if (Status s = MissionFlightConfig::validate(); !s) return Status::Error("mission/" + s.message());
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (Status s = checkReferenceWithinLimits(speed, yaw_rate, tracker.model.v_max, tracker.model.yaw_rate_max, "mission/",
                                            "tracker/");
      !s) {
    return s;
  }
  if (!positive(frame_rate) || frame_rate > 100.0) return Status::Error("mission/frame_rate expected in (0, 100] Hz");
  if (!positive(frontier_period)) return Status::Error("mission/frontier_period expected > 0");
  if (!(max_path_length >= 0.0) || !std::isfinite(max_path_length)) {
    return Status::Error("mission/max_path_length expected >= 0 m (0: no limit)");
  }
  if (!(start_free_radius >= 0.0) || start_free_radius > 10.0) {
    return Status::Error("mission/start_free_radius expected in [0, 10] m");
  }
  if (!positive(progress_period)) return Status::Error("mission/progress_period expected > 0");
  if (mesh_layer_queue < 1 || mesh_layer_queue > 4096) {
    return Status::Error("mission/mesh_layer_queue expected in [1, 4096] frames");
  }
  if (threads < 1 || threads > 64) return Status::Error("mission/threads expected in [1, 64]");
  if (Status s = pose_error.validate(); !s) return Status::Error("mission/" + s.message());
  if (Status s = manhattan_yaw.validate(); !s) return Status::Error("mission/" + s.message());
  return Status::Ok();
}

Status loadMissionConfigText(const std::string& text, const std::string& name, MissionConfig* c) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    return Status::Error("cannot read " + name + ": " + e.what());
  }
  return loadMissionConfigNode(root, name, c);
}

Status loadMissionConfig(const std::string& file, MissionConfig* c) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::Exception& e) {
    return Status::Error("cannot read '" + file + "': " + e.what());
  }
  return loadMissionConfigNode(root, file, c);
}

Status loadMissionConfigNode(const YAML::Node& root, const std::string& file, MissionConfig* c) {
  if (!root.IsMap()) return Status::Error("'" + file + "' is not a YAML map");

  YamlParamSource nbv(root["nbv"], "nbv", &c->given_keys);
  YamlParamSource sim(root["depth_sim"], "depth_sim", &c->given_keys);
  YamlParamSource trk(root["tracker"], "tracker", &c->given_keys);
  YamlParamSource m(root["mission"], "mission", &c->given_keys);
  if (Status s = loadMissionConfigFrom(nbv, sim, trk, m, c); !s) return Status::Error(file + ": " + s.message());
  return Status::Ok();
}

Status loadMissionConfigFrom(ParamSource& nbv, ParamSource& sim, ParamSource& trk, ParamSource& m, MissionConfig* c) {
  readTsdfKeys(nbv, &c->tsdf);
  readCameraKeys(nbv, &c->camera);
  readSurfaceKeys(nbv, &c->surface);
  readUtilityKeys(nbv, &c->explorer.graph);
  if (Status s = nbv.status(); !s) return s;
  readSceneKeys(sim, &c->scene);
  if (Status s = sim.status(); !s) return s;

  // The simulated UAV's limits, the keys mpc_tracker reads (its MPC keeps
  // the model's limits, as the node's does).
  readTrackerKeys(trk, &c->tracker);
  trk.refuseUnknown();
  if (Status s = trk.status(); !s) return s;

  m.get("start", &c->start);
  readFlightKeys(m, c);
  readExplorerKeys(m, &c->explorer);
  readPathKeys(m, &c->path);
  readPoseErrorKeys(m, &c->pose_error);
  readInvalidPixelsKey(m, "invalid_pixels", &c->tsdf);
  m.get("frame_rate", &c->frame_rate);
  m.get("frontier_period", &c->frontier_period);
  m.get("max_path_length", &c->max_path_length);
  m.get("start_free_radius", &c->start_free_radius);
  m.get("progress_period", &c->progress_period);
  m.get("mesh_layer_queue", &c->mesh_layer_queue);
  m.get("threads", &c->threads);
  m.get("seed", &c->seed);
  m.get("manhattan_yaw", &c->manhattan_yaw.enabled);
  m.get("manhattan_yaw_gain", &c->manhattan_yaw.gain);
  m.get("collision_radius", &c->path.collision_radius);
  m.get("epsilon", &c->surface.epsilon);
  m.get("parallel_distance", &c->surface.parallel_distance);
  m.get("parallel_cos", &c->surface.parallel_cos);
  m.refuseUnknown();
  if (Status s = m.status(); !s) return s;
  // The rays only serve pool_unknown_below and head_unknown: a mission with
  // neither skips them.
  c->surface.unknown_fraction =
      c->explorer.pool_unknown_below > 0.0 || (c->explorer.head_unknown && c->explorer.head_lookahead > 1);
  c->surface.camera = c->camera;
  c->explorer.gaze.camera = c->camera;
  c->surface.collision_radius = c->path.collision_radius;
  return Status::Ok();
}

std::string defaultConfigFile(const std::string& package_dir, const std::string& scene) {
  const std::string stem = std::filesystem::path(scene).stem().string();
  const std::string candidate = package_dir + "/config/" + stem + ".yaml";
  return std::filesystem::exists(candidate) ? candidate : std::string();
}

EvalConfig missionEvalConfig(const MissionConfig& c) {
  EvalConfig e;
  e.voxel_size = c.tsdf.voxel_size;
  e.min_range = c.camera.min_range;
  e.max_range = c.camera.max_range;
  e.collision_radius = c.path.collision_radius;
  e.threads = c.threads;
  return e;
}


}  // namespace surface_nbv
