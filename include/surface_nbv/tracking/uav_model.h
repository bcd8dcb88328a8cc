// A 4-DOF UAV model for simulation and MPC prediction: per axis a double
// integrator with linear drag (v' = a - drag * v, p' = v) and yaw as a single
// integrator of a rate command. World frame (z up), metres, seconds, radians.
// Acceleration is the net command beyond hover (gravity is the autopilot's job).
#pragma once

#include <string>

#include "surface_nbv/common.h"
#include "surface_nbv/util/angles.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct UavState {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();  // position of base_link
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();  // velocity
  double yaw = 0.0;                               // rad, kept in (-pi, pi]
  double yaw_rate = 0.0;                          // rad/s, the last applied command

  bool allFinite() const;
};

struct UavCommand {
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero();  // acceleration, m/s^2
  double yaw_rate = 0.0;                          // rad/s
};

struct UavModelConfig {
  double drag = 0.1;          // 1/s, linear drag coefficient (0 = pure double integrator)
  double v_max = 1.0;         // m/s, per axis (box)
  double a_max = 1.5;         // m/s^2, per axis (box)
  double yaw_rate_max = 1.0;  // rad/s

  // Names the first bad key, e.g. "v_max expected > 0".
  Status validate() const;
};

// Exact zero-order-hold discretization of one axis over dt:
//   v+ = alpha v + beta a,   p+ = p + beta v + gamma a.
struct AxisDiscretization {
  double alpha = 1.0, beta = 0.0, gamma = 0.0;
};
AxisDiscretization discretizeAxis(double drag, double dt);

// Legs are timed at a reference speed and yaw rate; a reference faster than
// the UAV's limits leaves it behind on every turn. Names the reference key and
// the limit it exceeds: `reference` and `limits` are key prefixes (e.g.
// "mission/" and "tracker/"). An infinite limit (one not known) passes.
Status checkReferenceWithinLimits(double speed, double yaw_rate, double v_max, double yaw_rate_max,
                                  const std::string& reference, const std::string& limits);

// The acceleration closest to `a` (NaN reads as 0) inside [-a_max, a_max] that
// keeps v+ inside [-v_max, v_max] after dt; when no such value exists (v already
// beyond the box), the one braking hardest. Always finite.
double clampAcceleration(double v, double a, double v_max, double a_max, const AxisDiscretization& d);


// Integrates UavState at a caller-chosen fixed step. Every command is clamped
// first (NaN -> 0, acceleration and yaw rate boxes, velocity box after the step),
// so the state stays finite and inside the limits whatever arrives.
class UavModel {
 public:
  explicit UavModel(const UavModelConfig& config, const UavState& initial = UavState());

  // Refuses a non-finite state; a velocity or yaw rate beyond the limits is clamped.
  Status reset(const UavState& state);
  // The command step() would apply for dt from the current state.
  UavCommand clamp(const UavCommand& command, double dt) const;
  // Applies clamp(command, dt) for dt seconds (dt <= 0 or non-finite: no-op).
  // Returns the applied command.
  UavCommand step(const UavCommand& command, double dt);

  const UavState& state() const { return state_; }
  const UavModelConfig& config() const { return config_; }

 private:
  UavModelConfig config_;
  UavState state_;
};

}  // namespace surface_nbv
