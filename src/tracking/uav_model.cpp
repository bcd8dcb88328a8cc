#include "surface_nbv/tracking/uav_model.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {

namespace {

bool positiveFinite(double x) { return std::isfinite(x) && x > 0.0; }

}  // namespace

bool UavState::allFinite() const {
  return p_W.allFinite() && v_W.allFinite() && std::isfinite(yaw) && std::isfinite(yaw_rate);
}

Status UavModelConfig::validate() const {
  if (!std::isfinite(drag) || drag < 0.0) return Status::Error("drag expected >= 0");
  if (!positiveFinite(v_max)) return Status::Error("v_max expected > 0");
  if (!positiveFinite(a_max)) return Status::Error("a_max expected > 0");
  if (!positiveFinite(yaw_rate_max)) return Status::Error("yaw_rate_max expected > 0");
  return Status::Ok();
}

Status checkReferenceWithinLimits(double speed, double yaw_rate, double v_max, double yaw_rate_max,
                                  const std::string& reference, const std::string& limits) {
  if (speed > v_max) {
    return Status::Error(reference + "speed expected <= " + limits + "v_max (the UAV's limit per axis)");
  }
  if (yaw_rate > yaw_rate_max) {
    return Status::Error(reference + "yaw_rate expected <= " + limits + "yaw_rate_max (the UAV's limit)");
  }
  return Status::Ok();
}

AxisDiscretization discretizeAxis(double drag, double dt) {
  AxisDiscretization d;
  const double x = drag * dt;
  if (x < 1e-6) {  // series: avoids cancellation for tiny drag
    d.alpha = 1.0 - x;
    d.beta = dt * (1.0 - 0.5 * x);
    d.gamma = 0.5 * dt * dt * (1.0 - x / 3.0);
  } else {
    d.alpha = std::exp(-x);
    d.beta = (1.0 - d.alpha) / drag;
    d.gamma = (dt - d.beta) / drag;
  }
  return d;
}

double clampAcceleration(double v, double a, double v_max, double a_max, const AxisDiscretization& d) {
  if (!std::isfinite(a)) a = 0.0;
  if (!std::isfinite(v)) v = 0.0;
  a = std::clamp(a, -a_max, a_max);
  if (d.beta <= 0.0) return a;
  // Accelerations keeping alpha v + beta a inside [-v_max, v_max].
  const double lo = (-v_max - d.alpha * v) / d.beta;
  const double hi = (v_max - d.alpha * v) / d.beta;
  if (lo > a_max) return a_max;    // far below the box: accelerate as hard as allowed
  if (hi < -a_max) return -a_max;  // far above the box: brake as hard as allowed
  return std::clamp(a, std::max(lo, -a_max), std::min(hi, a_max));
}


UavModel::UavModel(const UavModelConfig& config, const UavState& initial) : config_(config) {
  if (!reset(initial)) reset(UavState());
}

Status UavModel::reset(const UavState& state) {
  if (!state.allFinite()) return Status::Error("initial UAV state has a non-finite value");
  state_ = state;
  state_.v_W = state.v_W.cwiseMax(-config_.v_max).cwiseMin(config_.v_max);
  state_.yaw = wrapAngle(state.yaw);
  state_.yaw_rate = std::clamp(state.yaw_rate, -config_.yaw_rate_max, config_.yaw_rate_max);
  return Status::Ok();
}

UavCommand UavModel::clamp(const UavCommand& command, double dt) const {
  UavCommand out;
  const AxisDiscretization d = discretizeAxis(config_.drag, std::isfinite(dt) && dt > 0.0 ? dt : 0.0);
  for (int i = 0; i < 3; ++i) {
    out.a_W[i] = clampAcceleration(state_.v_W[i], command.a_W[i], config_.v_max, config_.a_max, d);
  }
  out.yaw_rate = std::isfinite(command.yaw_rate)
                     ? std::clamp(command.yaw_rate, -config_.yaw_rate_max, config_.yaw_rate_max)
                     : 0.0;
  return out;
}

UavCommand UavModel::step(const UavCommand& command, double dt) {
  if (!std::isfinite(dt) || dt <= 0.0) return UavCommand();
  const UavCommand u = clamp(command, dt);
  const AxisDiscretization d = discretizeAxis(config_.drag, dt);
  state_.p_W += d.beta * state_.v_W + d.gamma * u.a_W;
  state_.v_W = (d.alpha * state_.v_W + d.beta * u.a_W).cwiseMax(-config_.v_max).cwiseMin(config_.v_max);
  state_.yaw = wrapAngle(state_.yaw + dt * u.yaw_rate);
  state_.yaw_rate = u.yaw_rate;
  return u;
}

}  // namespace surface_nbv
