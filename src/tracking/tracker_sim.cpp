#include "surface_nbv/tracking/tracker_sim.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {

Status TrackerSimConfig::validate() const {
  if (!std::isfinite(sim_dt) || sim_dt <= 0.0 || sim_dt > 1.0) return Status::Error("sim_dt expected in (0, 1] s");
  const double ratio = control_period / sim_dt;
  if (!std::isfinite(control_period) || control_period < sim_dt || ratio > 1e6 ||
      std::abs(ratio - std::round(ratio)) > 1e-6 * ratio) {
    return Status::Error("control_period expected a whole multiple of sim_dt");
  }
  if (!std::isfinite(max_start_distance) || max_start_distance < 0.0) {
    return Status::Error("max_start_distance expected >= 0");
  }
  if (!std::isfinite(start_time) || std::abs(start_time) > 1e9) return Status::Error("start_time expected finite");
  if (Status s = model.validate(); !s) return Status::Error("model: " + s.message());
  if (Status s = mpc.validate(); !s) return Status::Error("mpc: " + s.message());
  return Status::Ok();
}

const char* toString(TrackerMode mode) {
  switch (mode) {
    case TrackerMode::kHolding: return "holding";
    case TrackerMode::kTracking: return "tracking";
    case TrackerMode::kFinished: return "finished";
  }
  return "unknown";
}

TrackerSim::TrackerSim(const TrackerSimConfig& config, const UavState& initial)
    : config_(config), model_(config.model, initial), mpc_(config.mpc, config.model) {
  steps_per_control_ = std::max<int64_t>(1, std::llround(config_.control_period / config_.sim_dt));
  hold();
}

void TrackerSim::holdAt(const Eigen::Vector3d& p_W, double yaw, TrackerMode mode) {
  hold_p_W_ = p_W;
  hold_yaw_ = yaw;
  mode_ = mode;
  next_control_step_ = steps_;  // respond at the next step
}

void TrackerSim::hold() {
  trajectory_ = Trajectory();
  holdAt(state().p_W, state().yaw, TrackerMode::kHolding);
}

Status TrackerSim::setTrajectory(const Trajectory& trajectory) {
  Status status = trajectory.validate(state().p_W, config_.max_start_distance);
  if (!status) {
    last_refusal_ = status.message();
    hold();
    return status;
  }
  last_refusal_.clear();
  trajectory_ = trajectory;
  mode_ = TrackerMode::kTracking;
  next_control_step_ = steps_;
  return status;
}

TrajectorySample TrackerSim::reference() const {
  if (mode_ == TrackerMode::kTracking) return trajectory_.sample(time());
  TrajectorySample s;
  s.p_W = hold_p_W_;
  s.yaw = hold_yaw_;
  return s;
}

MpcReference TrackerSim::buildReference() const {
  const int n = mpc_.horizon();
  if (mode_ != TrackerMode::kTracking) return MpcReference::hold(hold_p_W_, hold_yaw_, n);
  MpcReference r;
  r.p_W.resize(3, n);
  r.v_W.resize(3, n);
  r.yaw.resize(n);
  const double t = time();
  for (int k = 0; k < n; ++k) {
    const TrajectorySample s = trajectory_.sample(t + (k + 1) * config_.mpc.dt);
    r.p_W.col(k) = s.p_W;
    r.v_W.col(k) = s.v_W;
    r.yaw[k] = s.yaw;
  }
  return r;
}

void TrackerSim::step() {
  if (mode_ == TrackerMode::kTracking && time() > trajectory_.endTime()) {
    const TrajectoryPoint& last = trajectory_.points().back();
    holdAt(last.p_W, last.yaw, TrackerMode::kFinished);
  }
  if (steps_ >= next_control_step_) {
    last_solve_ = mpc_.solve(state(), buildReference(), command_);
    mpc_command_ = last_solve_.command;
    next_control_step_ = steps_ + steps_per_control_;
  }
  command_ = model_.step(mpc_command_, config_.sim_dt);
  ++steps_;
}

int64_t TrackerSim::runUntil(double t, int64_t max_steps) {
  int64_t taken = 0;
  while (taken < max_steps && time() < t) {
    step();
    ++taken;
  }
  return taken;
}

}  // namespace surface_nbv
