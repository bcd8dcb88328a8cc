#include "surface_nbv/tracking/mpc_tracker.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {

namespace {

bool nonNegative(double x) { return std::isfinite(x) && x >= 0.0; }

// D'D for the first-difference operator D (row 0 = e0, row k = e_k - e_k-1).
Eigen::MatrixXd differenceGram(int n) {
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n; ++k) {
    g(k, k) = k + 1 < n ? 2.0 : 1.0;
    if (k + 1 < n) g(k, k + 1) = g(k + 1, k) = -1.0;
  }
  return g;
}

Eigen::VectorXd stateWeights(int n, double weight, double terminal) {
  Eigen::VectorXd w = Eigen::VectorXd::Constant(n, weight);
  w[n - 1] *= terminal;
  return w;
}

// Moves the iterate one step forward in time: row k takes row k+1, the last repeats.
void shiftRows(Eigen::MatrixXd* m, int begin, int count) {
  if (count < 2 || m->rows() < begin + count) return;
  const Eigen::MatrixXd tail = m->middleRows(begin + 1, count - 1);
  m->middleRows(begin, count - 1) = tail;
}

UavCommand brakeCommand(const UavState& state, const UavModelConfig& model, const AxisDiscretization& d) {
  UavCommand u;
  if (!state.v_W.allFinite()) return u;
  for (int i = 0; i < 3; ++i) {
    const double stop = d.beta > 0.0 ? -d.alpha * state.v_W[i] / d.beta : 0.0;
    u.a_W[i] = clampAcceleration(state.v_W[i], stop, model.v_max, model.a_max, d);
  }
  return u;
}

}  // namespace

Status MpcConfig::validate() const {
  if (horizon < 1 || horizon > 200) return Status::Error("horizon expected in [1, 200]");
  if (!std::isfinite(dt) || dt <= 0.0 || dt > 10.0) return Status::Error("dt expected in (0, 10] s");
  if (!nonNegative(q_position)) return Status::Error("q_position expected >= 0");
  if (!nonNegative(q_velocity)) return Status::Error("q_velocity expected >= 0");
  if (!nonNegative(q_terminal)) return Status::Error("q_terminal expected >= 0");
  if (!nonNegative(r_acceleration)) return Status::Error("r_acceleration expected >= 0");
  if (!nonNegative(r_acceleration_change)) return Status::Error("r_acceleration_change expected >= 0");
  if (r_acceleration + r_acceleration_change <= 0.0) {
    return Status::Error("r_acceleration or r_acceleration_change expected > 0");
  }
  if (!nonNegative(q_yaw)) return Status::Error("q_yaw expected >= 0");
  if (!nonNegative(r_yaw_rate)) return Status::Error("r_yaw_rate expected >= 0");
  if (!nonNegative(r_yaw_rate_change)) return Status::Error("r_yaw_rate_change expected >= 0");
  if (r_yaw_rate + r_yaw_rate_change <= 0.0) return Status::Error("r_yaw_rate or r_yaw_rate_change expected > 0");
  if (!std::isfinite(jerk_max) || jerk_max <= 0.0) return Status::Error("jerk_max expected > 0");
  if (Status s = qp.validate(); !s) return Status::Error("qp: " + s.message());
  return Status::Ok();
}

MpcReference MpcReference::hold(const Eigen::Vector3d& p_W, double yaw, int horizon) {
  MpcReference r;
  r.p_W = p_W.replicate(1, horizon);
  r.v_W = Eigen::Matrix3Xd::Zero(3, horizon);
  r.yaw = Eigen::VectorXd::Constant(horizon, yaw);
  return r;
}

const char* toString(MpcStatus status) {
  switch (status) {
    case MpcStatus::kSolved: return "solved";
    case MpcStatus::kIterationLimit: return "iteration limit";
    case MpcStatus::kInvalidInput: return "invalid input";
  }
  return "unknown";
}

MpcTracker::MpcTracker(const MpcConfig& config, const UavModelConfig& model)
    : config_(config), model_(model), step_(discretizeAxis(model.drag, config.dt)) {
  const int n = config_.horizon;
  phi_p_.setZero(n, 2);
  phi_v_.setZero(n, 2);
  gamma_p_.setZero(n, n);
  gamma_v_.setZero(n, n);
  reach_.setZero(n);
  alpha_pow_.setZero(n);
  Eigen::RowVectorXd p = Eigen::RowVectorXd::Zero(2 + n), v = Eigen::RowVectorXd::Zero(2 + n);
  p[0] = 1.0;
  v[1] = 1.0;
  double reach = 0.0, alpha_pow = 1.0;
  for (int k = 0; k < n; ++k) {
    p += step_.beta * v;
    p[2 + k] += step_.gamma;
    v *= step_.alpha;
    v[2 + k] += step_.beta;
    phi_p_.row(k) = p.head(2);
    gamma_p_.row(k) = p.tail(n);
    phi_v_.row(k) = v.head(2);
    gamma_v_.row(k) = v.tail(n);
    reach = step_.alpha * reach + step_.beta;
    alpha_pow *= step_.alpha;
    reach_[k] = reach;
    alpha_pow_[k] = alpha_pow;
  }
  const Eigen::VectorXd wp = stateWeights(n, config_.q_position, config_.q_terminal);
  const Eigen::VectorXd wv = stateWeights(n, config_.q_velocity, config_.q_terminal);
  grad_p_ = gamma_p_.transpose() * wp.asDiagonal();
  grad_v_ = gamma_v_.transpose() * wv.asDiagonal();
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd P = grad_p_ * gamma_p_ + grad_v_ * gamma_v_ + config_.r_acceleration * identity +
                      config_.r_acceleration_change * differenceGram(n);
  P = 0.5 * (P + P.transpose()).eval();
  Eigen::MatrixXd difference = identity;
  difference.diagonal(-1).setConstant(-1.0);
  Eigen::MatrixXd A(3 * n, n);
  A << gamma_v_, identity, difference;
  position_qp_.setup(P, A, config_.qp);

  gamma_yaw_ = config_.dt * Eigen::MatrixXd(Eigen::MatrixXd::Ones(n, n).triangularView<Eigen::Lower>());
  grad_yaw_ = gamma_yaw_.transpose() * stateWeights(n, config_.q_yaw, config_.q_terminal).asDiagonal();
  Eigen::MatrixXd P_yaw =
      grad_yaw_ * gamma_yaw_ + config_.r_yaw_rate * identity + config_.r_yaw_rate_change * differenceGram(n);
  P_yaw = 0.5 * (P_yaw + P_yaw.transpose()).eval();
  yaw_qp_.setup(P_yaw, identity, config_.qp);
}

void MpcTracker::resetWarmStart() {
  position_iterate_ = QpIterate();
  yaw_iterate_ = QpIterate();
}

MpcResult MpcTracker::solve(const UavState& state, const MpcReference& reference, const UavCommand& previous) {
  const int n = config_.horizon;
  MpcResult result;
  if (!state.allFinite()) {
    result.status = MpcStatus::kInvalidInput;
    result.message = "UAV state is not finite";
    result.command = brakeCommand(state, model_, step_);
    result.predicted_p_W = Eigen::Matrix3Xd::Zero(3, n);
    resetWarmStart();
    return result;
  }
  MpcReference ref = reference;
  if (ref.p_W.cols() != n || ref.v_W.cols() != n || ref.yaw.size() != n || !ref.allFinite()) {
    result.status = MpcStatus::kInvalidInput;
    result.message = "reference has a non-finite value or not " + std::to_string(n) + " steps: holding pose";
    ref = MpcReference::hold(state.p_W, state.yaw, n);
  }
  const double a_max = model_.a_max, v_max = model_.v_max, r_max = model_.yaw_rate_max;
  const Eigen::Vector3d a_prev = previous.a_W.allFinite() ? previous.a_W : Eigen::Vector3d::Zero();
  const double r_prev = std::isfinite(previous.yaw_rate) ? previous.yaw_rate : 0.0;

  // Position axes: the three columns of one QP.
  Eigen::Matrix<double, 2, 3> x0;
  x0.row(0) = state.p_W.transpose();
  x0.row(1) = state.v_W.transpose();
  const Eigen::MatrixXd a_ref = (model_.drag * ref.v_W.transpose()).cwiseMax(-a_max).cwiseMin(a_max);
  Eigen::MatrixXd q = grad_p_ * (phi_p_ * x0 - ref.p_W.transpose()) + grad_v_ * (phi_v_ * x0 - ref.v_W.transpose()) -
                      config_.r_acceleration * a_ref;
  q.row(0) -= config_.r_acceleration_change * a_prev.transpose();
  Eigen::MatrixXd lo(3 * n, 3), hi(3 * n, 3);
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < n; ++k) {
      // Velocity box, widened where even the hardest input cannot reach it.
      const double free_v = alpha_pow_[k] * state.v_W[i];
      hi(k, i) = std::max(v_max, free_v - a_max * reach_[k]) - free_v;
      lo(k, i) = std::min(-v_max, free_v + a_max * reach_[k]) - free_v;
    }
  }
  const double jump = config_.jerk_max * config_.dt;
  lo.middleRows(n, n).setConstant(-a_max);
  hi.middleRows(n, n).setConstant(a_max);
  lo.bottomRows(n).setConstant(-jump);
  hi.bottomRows(n).setConstant(jump);
  lo.row(2 * n) += a_prev.transpose();
  hi.row(2 * n) += a_prev.transpose();
  shiftRows(&position_iterate_.x, 0, n);
  shiftRows(&position_iterate_.y, 0, n);
  shiftRows(&position_iterate_.y, n, n);
  shiftRows(&position_iterate_.y, 2 * n, n);
  const QpStatus position_status = position_qp_.solve(q, lo, hi, &position_iterate_);

  // Yaw relative to the current yaw, reference unwrapped step by step.
  Eigen::VectorXd yaw_ref(n);
  double previous_yaw = 0.0;
  for (int k = 0; k < n; ++k) {
    previous_yaw += wrapAngle(ref.yaw[k] - state.yaw - previous_yaw);
    yaw_ref[k] = previous_yaw;
  }
  Eigen::VectorXd rate_ref = Eigen::VectorXd::Zero(n);
  for (int k = 1; k < n; ++k) rate_ref[k] = std::clamp((yaw_ref[k] - yaw_ref[k - 1]) / config_.dt, -r_max, r_max);
  if (n > 1) rate_ref[0] = rate_ref[1];
  Eigen::VectorXd q_yaw = -grad_yaw_ * yaw_ref - config_.r_yaw_rate * rate_ref;
  q_yaw[0] -= config_.r_yaw_rate_change * r_prev;
  shiftRows(&yaw_iterate_.x, 0, n);
  shiftRows(&yaw_iterate_.y, 0, n);
  const QpStatus yaw_status = yaw_qp_.solve(q_yaw, Eigen::VectorXd::Constant(n, -r_max),
                                            Eigen::VectorXd::Constant(n, r_max), &yaw_iterate_);
  result.iterations = position_iterate_.iterations + yaw_iterate_.iterations;

  const bool position_ok = position_status == QpStatus::kSolved || position_status == QpStatus::kIterationLimit;
  const bool yaw_ok = yaw_status == QpStatus::kSolved || yaw_status == QpStatus::kIterationLimit;
  if (!position_ok || !yaw_ok || !position_iterate_.x.allFinite() || !yaw_iterate_.x.allFinite()) {
    result.status = MpcStatus::kInvalidInput;
    result.message = std::string("QP failed (position: ") + toString(position_status) + ", yaw: " +
                     toString(yaw_status) + "): braking";
    result.command = brakeCommand(state, model_, step_);
    result.predicted_p_W = state.p_W.replicate(1, n);
    resetWarmStart();
    return result;
  }
  if (result.status == MpcStatus::kSolved &&
      (position_status == QpStatus::kIterationLimit || yaw_status == QpStatus::kIterationLimit)) {
    result.status = MpcStatus::kIterationLimit;
    result.message = "QP stopped at qp.max_iterations";
  }
  for (int i = 0; i < 3; ++i) {
    // Jerk first; the velocity and acceleration boxes win when they disagree.
    const double smooth = std::clamp(position_iterate_.x(0, i), a_prev[i] - jump, a_prev[i] + jump);
    result.command.a_W[i] = clampAcceleration(state.v_W[i], smooth, v_max, a_max, step_);
  }
  result.command.yaw_rate = std::clamp(yaw_iterate_.x(0, 0), -r_max, r_max);
  result.predicted_p_W = (phi_p_ * x0 + gamma_p_ * position_iterate_.x).transpose();
  return result;
}

}  // namespace surface_nbv
