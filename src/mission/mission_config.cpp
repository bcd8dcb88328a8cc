#include "surface_nbv/mission/mission_config.h"

#include <cmath>
#include <filesystem>
#include <set>

#include <yaml-cpp/yaml.h>

#include "surface_nbv/mission/scene_defaults.h"

namespace surface_nbv {
namespace {

// Typed reads from one YAML map; the first failure is kept and named.
class YamlSection {
 public:
  // `given` (optional) collects "section/key" of every key present.
  YamlSection(const YAML::Node& node, std::string name, std::set<std::string>* given = nullptr)
      : node_(node), name_(std::move(name)), given_(given) {}

  bool present() const { return node_ && node_.IsMap(); }
  const Status& status() const { return status_; }

  template <typename T>
  void get(const std::string& key, T* value) {
    seen_.insert(key);
    if (!status_ || !present() || !node_[key]) return;
    if (given_) given_->insert(name_ + "/" + key);
    try {
      *value = node_[key].as<T>();
    } catch (const YAML::Exception& e) {
      fail(key, "has the wrong type");
    }
  }
  void getVector(const std::string& key, Eigen::Vector3d* v) {
    std::vector<double> values;
    get(key, &values);
    if (!status_ || !present() || !node_[key]) return;
    if (values.size() != 3) return fail(key, "expected [x, y, z]");
    *v = Eigen::Vector3d(values[0], values[1], values[2]);
  }
  void getVector4(const std::string& key, Eigen::Vector4d* v) {
    std::vector<double> values;
    get(key, &values);
    if (!status_ || !present() || !node_[key]) return;
    if (values.size() != 4) return fail(key, "expected [x, y, z, yaw]");
    *v = Eigen::Vector4d(values[0], values[1], values[2], values[3]);
  }
  YamlSection child(const std::string& key) {
    seen_.insert(key);
    return YamlSection(present() ? node_[key] : YAML::Node(), name_ + "/" + key, given_);
  }
  // Every key of the section must have been asked for.
  void refuseUnknown() {
    if (!status_ || !present()) return;
    for (const auto& kv : node_) {
      const std::string key = kv.first.as<std::string>();
      if (!seen_.count(key)) return fail(key, "is not a known key");
    }
  }
  void fail(const std::string& key, const std::string& why) {
    if (status_) status_ = Status::Error(name_ + "/" + key + " " + why);
  }

 private:
  YAML::Node node_;
  std::string name_;
  std::set<std::string>* given_ = nullptr;
  std::set<std::string> seen_;
  Status status_;
};

}  // namespace

// The body of loadMissionConfig on a parsed document; `file` names it in errors.
Status loadMissionConfigNode(const YAML::Node& root, const std::string& file, MissionConfig* c);

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
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(speed) || speed > 5.0) return Status::Error("mission/speed expected in (0, 5] m/s");
  if (!positive(yaw_rate) || yaw_rate > 5.0) return Status::Error("mission/yaw_rate expected in (0, 5] rad/s");
  if (Status s = checkReferenceWithinLimits(speed, yaw_rate, tracker.mpc.v_max, tracker.mpc.yaw_rate_max, "mission/",
                                            "tracker/");
      !s) {
    return s;
  }
  if (!positive(frame_rate) || frame_rate > 100.0) return Status::Error("mission/frame_rate expected in (0, 100] Hz");
  if (!positive(frontier_period)) return Status::Error("mission/frontier_period expected > 0");
  if (!(leg_lookahead >= 0.0) || leg_lookahead > 60.0) return Status::Error("mission/leg_lookahead expected in [0, 60] s");
  if (!(leg_yaw_tolerance > 0.0) || leg_yaw_tolerance > M_PI) {
    return Status::Error("mission/leg_yaw_tolerance expected in (0, pi] rad");
  }
  if (!positive(max_flight_time)) return Status::Error("mission/max_flight_time expected > 0");
  if (!(max_path_length >= 0.0) || !std::isfinite(max_path_length)) {
    return Status::Error("mission/max_path_length expected >= 0 m (0: no limit)");
  }
  if (!(start_free_radius >= 0.0) || start_free_radius > 10.0) {
    return Status::Error("mission/start_free_radius expected in [0, 10] m");
  }
  if (!(start_spin >= 0.0) || start_spin > 20.0) return Status::Error("mission/start_spin expected in [0, 20] rad");
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

  YamlSection nbv(root["nbv"], "nbv", &c->given_keys);
  nbv.get("voxel_size", &c->tsdf.voxel_size);
  double w_th = c->tsdf.w_th;
  nbv.get("w_th", &w_th);
  c->tsdf.w_th = static_cast<float>(w_th);
  double mesh_min_weight = c->tsdf.mesh_min_weight;
  nbv.get("mesh_min_weight", &mesh_min_weight);
  c->tsdf.mesh_min_weight = static_cast<float>(mesh_min_weight);
  nbv.get("truncation", &c->tsdf.truncation);
  nbv.get("mesh_truncation", &c->tsdf.mesh_truncation);
  nbv.get("mesh_voxel_size", &c->tsdf.mesh_voxel_size);
  nbv.get("weight_dropoff", &c->tsdf.weight_dropoff);
  nbv.get("mesh_weight_dropoff", &c->tsdf.mesh_weight_dropoff);
  nbv.getVector("bounds_min", &c->tsdf.bounds.min);
  nbv.getVector("bounds_max", &c->tsdf.bounds.max);
  YamlSection cam = nbv.child("camera");
  cam.get("width", &c->camera.width);
  cam.get("height", &c->camera.height);
  cam.get("hfov_deg", &c->camera.hfov_deg);
  cam.get("vfov_deg", &c->camera.vfov_deg);
  cam.get("min_range", &c->camera.min_range);
  cam.get("max_range", &c->camera.max_range);
  cam.get("rate_hz", &c->camera.rate_hz);
  cam.get("noise_k", &c->camera.noise_k);
  cam.get("noise_seed", &c->camera.noise_seed);
  cam.get("pitch_deg", &c->camera.pitch_deg);
  cam.get("noise_sigma0", &c->camera.sensor.noise_sigma0);
  cam.get("noise_sigma1", &c->camera.sensor.noise_sigma1);
  cam.get("lateral_noise_px", &c->camera.sensor.lateral_noise_px);
  cam.get("grazing_dropout_deg", &c->camera.sensor.grazing_dropout_deg);
  cam.get("dropout_rate", &c->camera.sensor.dropout_rate);
  cam.get("dropout_patch_fraction", &c->camera.sensor.dropout_patch_fraction);
  cam.get("dropout_patch_size", &c->camera.sensor.dropout_patch_size);
  cam.get("dropout_patch_rate", &c->camera.sensor.dropout_patch_rate);
  cam.get("quantization", &c->camera.sensor.quantization);
  nbv.get("delta_pose", &c->surface.delta_pose);
  nbv.get("d_nu", &c->surface.d_nu);
  nbv.get("d_nu_max", &c->surface.d_nu_max);
  nbv.get("approach_range_fraction", &c->surface.approach_range_fraction);
  nbv.get("lambda_tc", &c->explorer.graph.lambda_tc);
  nbv.get("lambda_ic", &c->explorer.graph.lambda_ic);
  if (!cam.status()) return Status::Error(file + ": " + cam.status().message());
  if (!nbv.status()) return Status::Error(file + ": " + nbv.status().message());

  YamlSection sim(root["depth_sim"], "depth_sim", &c->given_keys);
  sim.get("scene", &c->scene.scene);
  sim.get("scene_up_axis", &c->scene.transform.up_axis);
  sim.get("scene_scale", &c->scene.transform.scale);
  sim.getVector("scene_fit_size", &c->scene.transform.fit_size);
  sim.getVector("scene_offset", &c->scene.transform.offset);
  sim.getVector("crop_min", &c->scene.transform.crop.min);
  sim.getVector("crop_max", &c->scene.transform.crop.max);
  if (!sim.status()) return Status::Error(file + ": " + sim.status().message());

  // The simulated UAV's limits, the keys mpc_tracker reads (its MPC keeps
  // the model's limits, as the node's does).
  YamlSection trk(root["tracker"], "tracker", &c->given_keys);
  trk.get("drag", &c->tracker.model.drag);
  trk.get("v_max", &c->tracker.model.v_max);
  trk.get("a_max", &c->tracker.model.a_max);
  trk.get("yaw_rate_max", &c->tracker.model.yaw_rate_max);
  trk.get("jerk_max", &c->tracker.mpc.jerk_max);
  trk.refuseUnknown();
  if (!trk.status()) return Status::Error(file + ": " + trk.status().message());
  c->tracker.mpcUsesModelLimits();

  YamlSection m(root["mission"], "mission", &c->given_keys);
  m.getVector4("start", &c->start);
  m.get("speed", &c->speed);
  m.get("yaw_rate", &c->yaw_rate);
  m.get("frame_rate", &c->frame_rate);
  m.get("frontier_period", &c->frontier_period);
  m.get("leg_lookahead", &c->leg_lookahead);
  m.get("leg_yaw_tolerance", &c->leg_yaw_tolerance);
  m.get("max_flight_time", &c->max_flight_time);
  m.get("max_path_length", &c->max_path_length);
  m.get("start_free_radius", &c->start_free_radius);
  m.get("start_spin", &c->start_spin);
  m.get("progress_period", &c->progress_period);
  m.get("mesh_layer_queue", &c->mesh_layer_queue);
  m.get("threads", &c->threads);
  m.get("seed", &c->seed);
  m.get("pose_drift_rate", &c->pose_error.drift_rate);
  m.get("pose_yaw_drift_deg", &c->pose_error.yaw_drift_deg);
  m.get("pose_jitter", &c->pose_error.jitter_position);
  m.get("pose_jitter_deg", &c->pose_error.jitter_angle_deg);
  m.get("pose_error_seed", &c->pose_error.seed);
  m.get("manhattan_yaw", &c->manhattan_yaw.enabled);
  m.get("manhattan_yaw_gain", &c->manhattan_yaw.gain);
  m.get("collision_radius", &c->path.collision_radius);
  m.get("epsilon", &c->surface.epsilon);
  m.get("parallel_distance", &c->surface.parallel_distance);
  m.get("parallel_cos", &c->surface.parallel_cos);
  m.get("path_time_budget", &c->path.time_budget);
  m.get("path_iterations", &c->path.iteration_budget);
  m.get("path_lattice_step", &c->path.lattice_step);
  m.get("path_lattice_nodes", &c->path.lattice_max_nodes);
  m.get("match_radius", &c->explorer.match_radius);
  m.get("reach_tolerance", &c->explorer.reach_tolerance);
  m.get("max_failures", &c->explorer.max_failures);
  m.get("max_visits", &c->explorer.max_visits);
  m.get("blacklist_radius", &c->explorer.blacklist_radius);
  m.get("always_full", &c->explorer.always_full);
  m.get("full_on_leg_end", &c->explorer.full_on_leg_end);
  m.get("travel_yaw", &c->explorer.travel_yaw);
  m.get("turn_distance", &c->explorer.turn_distance);
  m.get("turn_lead", &c->explorer.turn_lead);
  m.get("reach_clearance", &c->explorer.reach_clearance);
  m.get("min_visible", &c->explorer.min_visible);
  m.get("head_lookahead", &c->explorer.head_lookahead);
  m.get("head_unknown", &c->explorer.head_unknown);
  m.get("head_lambda", &c->explorer.head_lambda);
  m.get("head_vertical_scale", &c->explorer.head_vertical_scale);
  m.get("gaze", &c->explorer.gaze.enabled);
  m.get("gaze_step", &c->explorer.gaze.step);
  m.get("gaze_min_ises", &c->explorer.gaze.min_ises);
  m.get("pool_unknown_below", &c->explorer.pool_unknown_below);
  // The rays only serve pool_unknown_below and head_unknown: a mission with
  // neither skips them.
  c->surface.unknown_fraction =
      c->explorer.pool_unknown_below > 0.0 || (c->explorer.head_unknown && c->explorer.head_lookahead > 1);
  m.get("path_distances", &c->explorer.path_distances);
  m.get("check_reachable", &c->explorer.check_reachable);
  m.get("empty_updates_before_done", &c->explorer.empty_updates_before_done);
  m.get("max_leg_attempts", &c->explorer.max_leg_attempts);
  m.get("leg_time_budget", &c->explorer.leg_time_budget);
  std::string objective = toString(c->explorer.graph.objective);
  m.get("tour_objective", &objective);
  std::string policy = toString(c->tsdf.invalid_pixels);
  m.get("invalid_pixels", &policy);
  m.refuseUnknown();
  if (!m.status()) return Status::Error(file + ": " + m.status().message());
  if (!parseInvalidPixelPolicy(policy, &c->tsdf.invalid_pixels)) {
    return Status::Error(file + ": mission/invalid_pixels expected 'ignore', 'clear' or 'clear_inf'");
  }
  if (!parseTourObjective(objective, &c->explorer.graph.objective)) {
    return Status::Error(file + ": mission/tour_objective expected 'product' or 'sum'");
  }
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

Status missionConfigFromArgs(const CliArgs& args, const std::string& package_dir, MissionConfig* config,
                             std::string* config_file) {
  *config_file = args.get("config", defaultConfigFile(package_dir, args.get("scene", "plant")));
  if (!config_file->empty()) {
    if (Status s = loadMissionConfig(*config_file, config); !s) return s;
  }
  return applySceneOptions(args, config);
}

}  // namespace surface_nbv
