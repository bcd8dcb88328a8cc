// Linear MPC for the 4-DOF UAV model (after Kamel et al. 2017): per axis a
// condensed QP over the N accelerations of the horizon (the three position
// axes share one Hessian and are solved together), and one QP over the N yaw
// rates. Box limits on velocity, acceleration and yaw rate (the UAV model's,
// UavModelConfig: the MPC has no limits of its own) and on jerk (the change of
// the acceleration command per step, from the previous command) are
// constraints of the QP (AdmmQpSolver); the applied input is projected exactly
// onto them (velocity and acceleration win over jerk when they disagree).
// Cost per step k = 1..N (k = N weighted by q_terminal):
//   q_position |p_k - p_ref|^2 + q_velocity |v_k - v_ref|^2
//   + r_acceleration |a - drag v_ref|^2 + r_acceleration_change |a_k - a_k-1|^2,
//   q_yaw (yaw_k - yaw_ref)^2 + r_yaw_rate (r - r_ref)^2 + r_yaw_rate_change (r_k - r_k-1)^2,
// where a_-1, r_-1 are the previous command: a new reference never makes the
// command jump. Deterministic; not thread-safe (it keeps the warm start).
#pragma once

#include <string>

#include "surface_nbv/tracking/qp_solver.h"
#include "surface_nbv/tracking/uav_model.h"

namespace surface_nbv {

struct MpcConfig {
  int horizon = 20;                     // N prediction steps
  double dt = 0.1;                      // s per prediction step
  double q_position = 10.0;
  double q_velocity = 2.0;
  double q_terminal = 5.0;              // factor on the last step's state weights
  double r_acceleration = 0.1;
  double r_acceleration_change = 2.0;
  double q_yaw = 10.0;
  double r_yaw_rate = 0.1;
  double r_yaw_rate_change = 1.0;
  double jerk_max = 5.0;                // m/s^3 per axis: |a_k - a_k-1| <= jerk_max dt
  QpSettings qp;

  // Names the first bad key, e.g. "horizon expected in [1, 200]".
  Status validate() const;
};

// The reference at the N prediction steps: column k-1 is the reference at
// t + k dt, for k = 1..N. Yaw in radians, any branch (unwrapped internally).
struct MpcReference {
  Eigen::Matrix3Xd p_W;
  Eigen::Matrix3Xd v_W;
  Eigen::VectorXd yaw;

  // A reference holding p_W and yaw at rest for `horizon` steps.
  static MpcReference hold(const Eigen::Vector3d& p_W, double yaw, int horizon);
  bool allFinite() const { return p_W.allFinite() && v_W.allFinite() && yaw.allFinite(); }
};

enum class MpcStatus {
  kSolved,          // both QPs converged
  kIterationLimit,  // a QP stopped at max_iterations: the input is still feasible
  kInvalidInput,    // non-finite state, or reference of the wrong size: braking command
};
const char* toString(MpcStatus status);

struct MpcResult {
  UavCommand command;               // finite and inside the model's limits, always
  MpcStatus status = MpcStatus::kSolved;
  int iterations = 0;               // ADMM iterations, position + yaw
  Eigen::Matrix3Xd predicted_p_W;   // N predicted positions (for display)
  std::string message;              // why, when status != kSolved
};

class MpcTracker {
 public:
  // Preconditions: config.validate() and model.validate() pass. Plans with
  // the model's drag and its limits (v_max, a_max, yaw_rate_max).
  MpcTracker(const MpcConfig& config, const UavModelConfig& model);

  // One control step from `state`; `previous` is the command applied so far.
  // A reference with a non-finite value is replaced by holding the state's pose.
  MpcResult solve(const UavState& state, const MpcReference& reference, const UavCommand& previous);
  // Forgets the warm start (the next solve starts from zero).
  void resetWarmStart();

  const MpcConfig& config() const { return config_; }
  // The model planned with, whose limits bound every command.
  const UavModelConfig& model() const { return model_; }
  int horizon() const { return config_.horizon; }

 private:
  MpcConfig config_;
  UavModelConfig model_;
  AxisDiscretization step_;
  // Position: v = Phi_v x0 + Gamma_v U and p = Phi_p x0 + Gamma_p U (x0 = [p0, v0]).
  Eigen::MatrixXd phi_p_, phi_v_, gamma_p_, gamma_v_;
  Eigen::MatrixXd grad_p_, grad_v_;  // Gamma' Q for the linear term
  Eigen::VectorXd reach_;            // sum_{j<k} alpha^j beta: the velocity reachable in k steps at a_max = 1
  Eigen::VectorXd alpha_pow_;        // alpha^k
  AdmmQpSolver position_qp_, yaw_qp_;
  Eigen::MatrixXd gamma_yaw_, grad_yaw_;
  QpIterate position_iterate_, yaw_iterate_;
};

}  // namespace surface_nbv
