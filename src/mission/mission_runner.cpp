#include "surface_nbv/mission/mission_runner.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/manhattan_yaw.h"
#include "surface_nbv/map/tsdf_integrator.h"
#include "surface_nbv/mission/oracle_gain.h"
#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/planning/mission_supervisor.h"
#include "surface_nbv/sensor/camera_mount.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/surface/frontier_builder.h"
#include "surface_nbv/tracking/tracker_sim.h"

namespace surface_nbv {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

Trajectory legTrajectory(const std::vector<Eigen::Vector4d>& path, const UavState& state, double t0,
                         double speed, double yaw_rate) {
  std::vector<Waypoint> waypoints;
  waypoints.push_back({state.p_W, state.yaw});
  for (const Eigen::Vector4d& q : path) waypoints.push_back({q.head<3>(), q.w()});
  return timeWaypoints(waypoints, t0, speed, yaw_rate);
}

// Where a trajectory ends, [x, y, z, yaw].
Eigen::Vector4d trajectoryEnd(const Trajectory& t) {
  const TrajectoryPoint& end = t.points().back();
  return Eigen::Vector4d(end.p_W.x(), end.p_W.y(), end.p_W.z(), end.yaw);
}

// A decision slower than this (wall) is reported on stderr as it happens.
constexpr double kSlowDecisionMs = 3000.0;

}  // namespace

MissionRunner::MissionRunner(const MissionConfig& config, const RaycastScene& scene)
    : config_(config), scene_(scene) {}

MissionRunner::~MissionRunner() = default;

const TsdfMap& MissionRunner::map() const { return *map_; }

const TsdfMap& MissionRunner::meshMap() const { return mesh_layer_ ? mesh_layer_->map() : *map_; }

double MissionRunner::observedFraction() const {
  if (probe_.empty() || !map_) return -1.0;
  size_t seen = 0;
  for (const Eigen::Vector3d& p : probe_) seen += surfaceObserved(*map_, p) ? 1 : 0;
  return static_cast<double>(seen) / probe_.size();
}

MissionResult MissionRunner::run() {
  const auto wall0 = Clock::now();
  MissionResult result;
  if (Status s = config_.validate(); !s) {
    result.status = s;
    return result;
  }
  const MissionConfig& c = config_;
  TsdfConfig tsdf = c.tsdf;
  tsdf.threads = c.threads;
  map_ = std::make_unique<TsdfMap>(tsdf);
  TsdfIntegrator integrator(map_.get());
  // One integrated frame per 1 / frame_rate stands for the camera's frames
  // in that time (rate_hz / frame_rate of them): the same weight per second.
  integrator.setWeightScale(std::max(1.0, c.camera.rate_hz / c.frame_rate));
  mesh_layer_ = std::make_unique<MeshLayer>(map_.get());
  mesh_layer_->setQueueDepth(static_cast<size_t>(c.mesh_layer_queue));
  mesh_layer_->setWeightScale(integrator.weightScale());
  CameraConfig camera_config = c.camera;
  camera_config.noise_seed = c.camera.noise_seed + c.seed;
  const DepthCamera camera(camera_config);
  const DepthRenderer renderer(scene_, camera, c.threads);
  const Transform T_B_C = opticalInBody(camera_config);
  PoseErrorConfig pose_config = c.pose_error;
  pose_config.seed = c.pose_error.seed + c.seed;
  PoseErrorModel pose_error(pose_config);
  // Heading from the structure (c.manhattan_yaw): `correction` takes the
  // odometry's estimate into the map's world; the planner and the map use
  // it, the tracker flies the estimate.
  ManhattanYaw manhattan(c.manhattan_yaw);
  Transform correction = Transform::Identity();
  const auto correctionYaw = [&] { return std::atan2(correction.linear()(1, 0), correction.linear()(0, 0)); };
  const auto toMap = [&](const Eigen::Vector4d& q) {
    const Eigen::Vector3d p = correction * Eigen::Vector3d(q.head<3>());
    return Eigen::Vector4d(p.x(), p.y(), p.z(), q.w() + correctionYaw());
  };
  const auto toEstimate = [&](const Eigen::Vector4d& q) {
    const Eigen::Vector3d p = correction.inverse() * Eigen::Vector3d(q.head<3>());
    return Eigen::Vector4d(p.x(), p.y(), p.z(), q.w() - correctionYaw());
  };
  SurfaceConfig surface = c.surface;
  surface.threads = c.threads;
  FrontierBuilder builder(surface);
  PathPlannerConfig path = c.path;
  path.seed = c.seed;
  Explorer explorer(c.explorer, path);
  std::unique_ptr<OracleGain> oracle;
  bool oracle_stale = true;  // the map changed since the oracle's last update
  if (oracle_gain_ && !probe_.empty()) {
    oracle = std::make_unique<OracleGain>(scene_, camera_config, probe_);
    explorer.setHeadGain([&](const Eigen::Vector4d& q) {
      if (oracle_stale) oracle->update(*map_), oracle_stale = false;
      return (*oracle)(q);
    });
  }

  if (c.start_free_radius > 0.0) {
    Status s = integrator.markFree(c.start.head<3>(), c.start_free_radius);
    if (s) s = mesh_layer_->markFree(c.start.head<3>(), c.start_free_radius);
    if (!s) {
      result.status = s;
      return result;
    }
  }
  CollisionMap collision(*map_, c.collision);
  if (Status s = explorer.setMap(&collision, tsdf.bounds); !s) {
    result.status = s;
    return result;
  }
  UavState initial;
  initial.p_W = c.start.head<3>();
  initial.yaw = c.start.w();
  TrackerSim tracker(c.tracker, initial);
  // The mission's rules (take-off spin, leg ends, decisions every
  // frontier_period, limits) are the supervisor's; this loop carries them out.
  MissionSupervisor supervisor(c.supervisorConfig());
  supervisor.setRecording(recording_);
  // A leg is flown on the estimate; the supervisor compares its end with the
  // UAV in the map's world.
  const auto fly = [&](const std::vector<Eigen::Vector4d>& leg) {
    const Trajectory t = legTrajectory(leg, tracker.state(), tracker.time(), c.speed, c.yaw_rate);
    const Status s = tracker.setTrajectory(t);
    if (s) {
      const Eigen::Vector4d end = trajectoryEnd(t);
      supervisor.legSent(c.manhattan_yaw.enabled ? toMap(end) : end, t.points().back().t);
    }
    return s;
  };
  // Take-off: turn in place to see around before the first plan.
  if (const std::vector<Eigen::Vector4d> spin = supervisor.takeOff(c.start); !spin.empty()) {
    if (Status s = fly(spin); !s) {
      result.status = Status::Error("take-off spin refused: " + s.message());
      return result;
    }
  }

  const double frame_dt = 1.0 / c.frame_rate;
  double next_frame = 0.0;
  double next_progress = 0.0;
  double next_checkpoint = checkpoint_period_ > 0.0 ? checkpoint_period_ : std::numeric_limits<double>::infinity();
  double last_checkpoint = 0.0;
  Frontier frontier;
  DepthImage depth;
  Eigen::Vector3d last_p = tracker.state().p_W;
  while (supervisor.limitReached(tracker.time(), result.path_length).empty()) {
    // Fly to the next frame time.
    const auto t_track = Clock::now();
    while (tracker.time() + 1e-9 < next_frame) {
      tracker.step();
      result.path_length += (tracker.state().p_W - last_p).norm();
      last_p = tracker.state().p_W;
    }
    result.times.tracker += msSince(t_track);
    next_frame += frame_dt;
    const UavState& state = tracker.state();
    Eigen::Vector4d uav(state.p_W.x(), state.p_W.y(), state.p_W.z(), state.yaw);
    // Sense. The UAV flies on its estimated pose; the camera is at the true
    // one and the frame is fused at the pose odometry reports (pose_error.h).
    const Transform T_W_C_estimate = levelBodyPose(state.p_W, state.yaw) * T_B_C;
    pose_error.advance(state.p_W, result.frames);
    Transform T_W_C = pose_error.reportedPose(T_W_C_estimate, result.frames);
    const auto t_render = Clock::now();
    renderer.render(pose_error.truePose(T_W_C_estimate), &depth, result.frames);
    result.times.render += msSince(t_render);
    if (c.manhattan_yaw.enabled) {
      T_W_C = correction * T_W_C;
      const double dyaw = manhattan.update(camera, depth, T_W_C);
      Transform turn = Transform::Identity();  // about the camera, so its position stays
      turn.linear() = Eigen::AngleAxisd(dyaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      turn.translation() = T_W_C.translation() - turn.linear() * T_W_C.translation();
      correction = turn * correction;
      T_W_C = turn * T_W_C;
      uav = toMap(uav);
      result.yaw_corrections = manhattan.corrections();
    }
    if (pose_error.enabled()) result.fused_pose_error.addPose(T_W_C, pose_error.truePose(T_W_C_estimate));
    const auto t_integrate = Clock::now();
    // The mesh layer fuses each frame on a thread of its own while the
    // mission goes on (the same layer as fusing it here, see mesh_layer.h).
    const Status fused = mesh_layer_->integrateDepthBehind(&integrator, camera, depth, T_W_C, c.threads);
    if (!fused) {
      result.status = Status::Error("integration failed at t = " + std::to_string(tracker.time()) + ": " + fused.message());
      break;
    }
    result.times.integrate += msSince(t_integrate);
    ++result.frames;
    result.flown.push_back(uav);
    result.flown_t.push_back(tracker.time());
    if (checkpoint_ && tracker.time() + 1e-9 >= next_checkpoint) {
      if (Status s = mesh_layer_->finish(); !s) {
        result.status = Status::Error("mesh layer integration failed: " + s.message());
        break;
      }
      checkpoint_(tracker.time(), result.path_length, meshMap());
      last_checkpoint = tracker.time();
      next_checkpoint += checkpoint_period_;
    }

    SupervisorInput in;
    in.t = tracker.time();
    in.uav = uav;
    in.path_length = result.path_length;
    in.tracker_finished = tracker.mode() == TrackerMode::kFinished;
    in.has_target = explorer.hasTarget();
    if (supervisor.poll(in) != SupervisorStep::kDecide) continue;

    // Map -> collision map -> frontier -> decision.
    const auto t_collision = Clock::now();
    collision.update(*map_);
    explorer.mapChanged();
    oracle_stale = true;
    const double collision_ms = msSince(t_collision);
    result.times.collision += collision_ms;
    const auto t_frontier = Clock::now();
    if (Status s = builder.update(*map_, collision, &frontier); !s) {
      result.status = Status::Error("frontier update failed: " + s.message());
      break;
    }
    const double frontier_ms = msSince(t_frontier);
    result.times.frontier += frontier_ms;
    result.times.frontier_ises += frontier.stats.ise_ms;
    result.times.frontier_poses += frontier.stats.viewpoints_ms;
    result.times.frontier_merge += frontier.stats.merge_ms;
    result.times.frontier_visibility += frontier.stats.visibility_ms;
    result.times.frontier_clusters += frontier.stats.clusters_ms;
    result.max_frontier_ms = std::max(result.max_frontier_ms, frontier_ms);
    ++result.frontier_updates;
    const ExplorerDecision d = supervisor.decide(&explorer, frontier, in);
    result.times.graph += d.timings.graph_ms;
    result.times.tour += d.timings.tour_ms;
    result.times.path += d.timings.path_ms;
    result.max_plan_ms = std::max(result.max_plan_ms, d.timings.total_ms);
    if (d.timings.total_ms > kSlowDecisionMs) {
      std::fprintf(stderr, "  slow decision at %.0f s of flight: %.1f s wall (%s, %s) at [%.1f %.1f %.1f], %zu failed legs so far: %s\n",
                   tracker.time(), 1e-3 * d.timings.total_ms, toString(d.action), toString(d.reason), uav.x(), uav.y(),
                   uav.z(), explorer.stats().leg_failures, d.message.c_str());
    }

    MissionEvent event;
    event.t = tracker.time();
    event.path_length = result.path_length;
    event.uav = uav;
    event.collision_ms = collision_ms;
    event.frontier_ms = frontier_ms;
    event.graph_ms = d.timings.graph_ms;
    event.tour_ms = d.timings.tour_ms;
    event.path_ms = d.timings.path_ms;
    event.full_recompute = d.full_recompute;
    event.ises = frontier.ises.size();
    event.inside = frontier.insideCount();
    event.remaining = frontier.remaining;
    event.viewpoints = frontier.viewpoints.size();
    event.clusters = frontier.clusters.size();
    event.tour = explorer.tour().size();
    event.roadmap = explorer.stats().roadmap_vertices;
    event.action = toString(d.action);
    event.reason = toString(d.reason);
    event.message = d.message;
    event.leg_failures = explorer.stats().leg_failures;
    const bool done = d.action == ExplorerAction::kDone;
    if (event.t >= next_progress || done) {
      event.observed = observedFraction();
      next_progress = event.t + c.progress_period;
      if (progress_) progress_(event);
    }
    result.events.push_back(event);

    if (done) {
      result.completed = supervisor.completed();
      result.end_reason = supervisor.endReason();
      break;
    }
    if (d.action == ExplorerAction::kFly) {
      std::vector<Eigen::Vector4d> leg = d.path;  // in the map's world: flown on the estimate
      if (c.manhattan_yaw.enabled) {
        for (Eigen::Vector4d& q : leg) q = toEstimate(q);
      }
      if (!fly(leg)) tracker.hold(), supervisor.legDropped();
    } else if (d.action == ExplorerAction::kHover) {
      tracker.hold();
      supervisor.legDropped();
    }
  }
  if (Status s = mesh_layer_->finish(); !s && result.status) {
    result.status = Status::Error("mesh layer integration failed: " + s.message());
  }
  if (checkpoint_ && result.status && tracker.time() > last_checkpoint + 1e-9) {
    checkpoint_(tracker.time(), result.path_length, meshMap());
  }
  if (result.end_reason.empty() && result.status) {
    result.end_reason = supervisor.limitReached(tracker.time(), result.path_length);
  }
  result.tally = supervisor.tally();
  result.flight_time = tracker.time();
  result.pose_error = pose_error.stats();
  result.explorer = explorer.stats();
  result.blacklisted = explorer.blacklist().size();
  result.final_ises = frontier.ises.size();
  result.final_inside = frontier.insideCount();
  result.wall_time = std::chrono::duration<double>(Clock::now() - wall0).count();
  return result;
}

}  // namespace surface_nbv
