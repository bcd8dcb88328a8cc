#include "surface_nbv/planning/mission_supervisor.h"

#include <algorithm>
#include <cmath>

#include "surface_nbv/util/angles.h"

namespace surface_nbv {

Status MissionFlightConfig::validate() const {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(speed) || speed > 20.0) return Status::Error("speed expected in (0, 20] m/s");
  if (!positive(yaw_rate) || yaw_rate > 10.0) return Status::Error("yaw_rate expected in (0, 10] rad/s");
  if (!(leg_lookahead >= 0.0) || leg_lookahead > 60.0) return Status::Error("leg_lookahead expected in [0, 60] s");
  if (!(leg_yaw_tolerance > 0.0) || leg_yaw_tolerance > M_PI) {
    return Status::Error("leg_yaw_tolerance expected in (0, pi] rad");
  }
  if (!(max_flight_time >= 0.0) || !std::isfinite(max_flight_time)) {
    return Status::Error("max_flight_time expected >= 0 s (0: no limit)");
  }
  if (!(start_spin >= 0.0) || start_spin > 20.0) return Status::Error("start_spin expected in [0, 20] rad");
  return Status::Ok();
}

void SupervisorTally::writeJson(JsonWriter* json) const {
  json->value("decisions_fly", fly).value("decisions_hover", hover);
  json->value("decisions_continue", cont).value("decisions_done", done);
  std::vector<double> s = decision_ms;
  std::sort(s.begin(), s.end());
  double total = 0.0;
  for (double ms : s) total += ms;
  json->value("decisions", s.size()).value("decision_wall_s_total", 1e-3 * total);
  json->value("decision_wall_s_median", s.empty() ? 0.0 : 1e-3 * s[s.size() / 2]);
  json->value("decision_wall_s_p90", s.empty() ? 0.0 : 1e-3 * s[s.size() * 9 / 10]);
  json->value("decision_wall_s_max", s.empty() ? 0.0 : 1e-3 * s.back());
  json->value("legs_sent", legs_sent).value("legs_dropped", legs_dropped);
}

namespace {

SupervisorCall call(SupervisorCall::Kind kind, const SupervisorInput& in = SupervisorInput()) {
  SupervisorCall c;
  c.kind = kind;
  c.in = in;
  return c;
}

SupervisorCall call(SupervisorCall::Kind kind, const ExplorerDecision& d, const SupervisorInput& in) {
  SupervisorCall c = call(kind, in);
  c.action = d.action;
  c.reason = d.reason;
  c.message = d.message;
  c.decision_ms = d.timings.total_ms;
  return c;
}

}  // namespace

MissionSupervisor::MissionSupervisor(const SupervisorConfig& config) : config_(config) {}

void MissionSupervisor::reset() {
  have_leg_ = spinning_ = done_ = completed_ = leg_ended_ = false;
  next_frontier_ = 0.0;
  end_reason_.clear();
  tally_ = SupervisorTally();
}

std::vector<Eigen::Vector4d> MissionSupervisor::takeOff(const Eigen::Vector4d& uav) {
  std::vector<Eigen::Vector4d> spin;
  const double turn = config_.flight.start_spin;
  if (turn > 0.0) {
    // Quarter turns at most, so the yaw interpolates the way it is meant to.
    const int steps = std::max(1, static_cast<int>(std::ceil(turn / (0.5 * M_PI))));
    for (int k = 1; k <= steps; ++k) spin.emplace_back(uav.x(), uav.y(), uav.z(), uav.w() + turn * k / steps);
  }
  if (recording_) {
    SupervisorInput in;
    in.uav = uav;
    recording_->push_back(call(SupervisorCall::Kind::kTakeOff, in));
    recording_->back().spin = spin.size();
  }
  spinning_ = !spin.empty();
  // Without a spin the first poll decides (the period's clock starts at 0).
  next_frontier_ = spinning_ ? std::numeric_limits<double>::infinity() : 0.0;
  return spin;
}

void MissionSupervisor::legSent(const Eigen::Vector4d& goal, double t_end) {
  if (recording_) {
    SupervisorCall c = call(SupervisorCall::Kind::kLegSent);
    c.goal = goal;
    c.t_end = t_end;
    recording_->push_back(c);
  }
  have_leg_ = true;
  leg_goal_ = goal;
  leg_end_ = t_end;
  ++tally_.legs_sent;
}

void MissionSupervisor::legDropped() {
  if (recording_) recording_->push_back(call(SupervisorCall::Kind::kLegDropped));
  if (have_leg_) ++tally_.legs_dropped;
  have_leg_ = false;
  if (spinning_) spinning_ = false, next_frontier_ = 0.0;
}

std::string MissionSupervisor::limitReached(double t, double path_length) const {
  const MissionFlightConfig& f = config_.flight;
  if (f.max_flight_time > 0.0 && !(t < f.max_flight_time)) {
    return "max_flight_time: " + std::to_string(f.max_flight_time) + " s of flight reached";
  }
  if (config_.max_path_length > 0.0 && !(path_length < config_.max_path_length)) {
    return "max_path_length: " + std::to_string(config_.max_path_length) + " m of path reached";
  }
  return "";
}

bool MissionSupervisor::legEnded(const SupervisorInput& in) const {
  if (in.tracker_finished) return true;
  if (!have_leg_) return false;
  if (config_.leg_settle >= 0.0 && in.t >= leg_end_ + config_.leg_settle) return true;
  const double lookahead = config_.flight.leg_lookahead;
  return lookahead > 0.0 && in.t + lookahead >= leg_end_ &&
         (in.uav.head<3>() - leg_goal_.head<3>()).norm() <= config_.reach_tolerance &&
         std::abs(wrapAngle(in.uav.w() - leg_goal_.w())) <= config_.flight.leg_yaw_tolerance;
}

SupervisorStep MissionSupervisor::poll(const SupervisorInput& in) {
  const SupervisorStep step = nextStep(in);
  if (recording_) {
    SupervisorCall c = call(SupervisorCall::Kind::kPoll, in);
    c.step = step;
    recording_->push_back(c);
  }
  return step;
}

SupervisorStep MissionSupervisor::nextStep(const SupervisorInput& in) {
  if (done_) return SupervisorStep::kDone;
  leg_ended_ = legEnded(in);
  if (spinning_) {
    if (!leg_ended_) return SupervisorStep::kWait;
    spinning_ = have_leg_ = false;
    next_frontier_ = in.t;  // decide now
  }
  const bool due = config_.frontier_period > 0.0 ? in.t + 1e-9 >= next_frontier_
                                                 : in.frontier_new || std::isfinite(next_frontier_);
  if (!due && !(leg_ended_ && in.has_target)) return SupervisorStep::kWait;
  return SupervisorStep::kDecide;
}

ExplorerDecision MissionSupervisor::decide(Explorer* explorer, const Frontier& frontier, const SupervisorInput& in) {
  ExplorerDecision d = explorer->update(frontier, in.uav, leg_ended_);
  decided(d, in);
  return d;
}

void MissionSupervisor::decided(const ExplorerDecision& d, const SupervisorInput& in) {
  if (recording_) recording_->push_back(call(SupervisorCall::Kind::kDecided, d, in));
  // Period 0: next_frontier_ finite means "decide at the next poll" (after
  // the spin); a decision clears it.
  next_frontier_ = config_.frontier_period > 0.0 ? in.t + config_.frontier_period
                                                 : std::numeric_limits<double>::infinity();
  if (leg_ended_) have_leg_ = false;  // this decision answers its end
  tallied(d);
}

void MissionSupervisor::record(const ExplorerDecision& d) {
  if (recording_) recording_->push_back(call(SupervisorCall::Kind::kRecord, d, SupervisorInput()));
  tallied(d);
}

void MissionSupervisor::tallied(const ExplorerDecision& d) {
  tally_.decision_ms.push_back(d.timings.total_ms);
  tally_.max_decision_ms = std::max(tally_.max_decision_ms, d.timings.total_ms);
  switch (d.action) {
    case ExplorerAction::kFly: ++tally_.fly; break;
    case ExplorerAction::kHover: ++tally_.hover; break;
    case ExplorerAction::kContinue: ++tally_.cont; break;
    case ExplorerAction::kDone:
      ++tally_.done;
      done_ = true;
      completed_ = d.reason == ReplanReason::kComplete;
      end_reason_ = std::string(toString(d.reason)) + ": " + d.message;
      break;
  }
}

}  // namespace surface_nbv
