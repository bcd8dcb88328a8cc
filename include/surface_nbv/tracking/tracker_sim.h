// The simulated UAV that the mpc_tracker node runs: a UavModel integrated at a
// fixed step sim_dt, an MpcTracker re-solved every control_period (the command
// is held in between), and the trajectory being followed. Time is counted in
// whole steps from start_time (s), so a run repeats exactly. A refused
// trajectory leaves the UAV holding its current pose; a finished one leaves it
// holding the last point. Not thread-safe.
#pragma once

#include <cstdint>
#include <string>

#include "surface_nbv/tracking/mpc_tracker.h"
#include "surface_nbv/tracking/trajectory.h"
#include "surface_nbv/tracking/uav_model.h"

namespace surface_nbv {

struct TrackerSimConfig {
  double sim_dt = 0.01;              // s, integration step
  double control_period = 0.1;       // s, a whole multiple of sim_dt
  double max_start_distance = 2.0;   // m, farther first points are refused
  double start_time = 0.0;           // s, the clock at step 0
  // The UAV's limits (v_max, a_max, yaw_rate_max), which the MPC plans with.
  UavModelConfig model;
  MpcConfig mpc;

  // Names the first bad key.
  Status validate() const;
};

enum class TrackerMode {
  kHolding,   // no trajectory yet, or the last one was refused: holding a pose
  kTracking,  // following the trajectory
  kFinished,  // past the trajectory's end: holding its last point
};
const char* toString(TrackerMode mode);

class TrackerSim {
 public:
  // Preconditions: config.validate() passes; a non-finite initial state is
  // replaced by the origin at rest. Holds the initial pose.
  explicit TrackerSim(const TrackerSimConfig& config, const UavState& initial = UavState());

  // Follows `trajectory` from the current state and command (no jump), or
  // refuses it (Status names why) and holds the current pose.
  Status setTrajectory(const Trajectory& trajectory);
  // Drops the trajectory and holds the current pose.
  void hold();
  // Advances one sim_dt (solving the MPC when a control period starts).
  void step();
  // Steps until time() >= t (at most `max_steps`); returns the steps taken.
  int64_t runUntil(double t, int64_t max_steps = 100000000);

  double time() const { return config_.start_time + static_cast<double>(steps_) * config_.sim_dt; }
  int64_t steps() const { return steps_; }
  const UavState& state() const { return model_.state(); }
  // The command applied during the last step (finite, inside the model's limits).
  const UavCommand& command() const { return command_; }
  TrackerMode mode() const { return mode_; }
  const Trajectory& trajectory() const { return trajectory_; }
  // The reference position and yaw of the current time.
  TrajectorySample reference() const;
  const MpcResult& lastSolve() const { return last_solve_; }
  // Why the last trajectory was refused (empty when the last was accepted).
  const std::string& lastRefusal() const { return last_refusal_; }
  const TrackerSimConfig& config() const { return config_; }

 private:
  MpcReference buildReference() const;
  void holdAt(const Eigen::Vector3d& p_W, double yaw, TrackerMode mode);

  TrackerSimConfig config_;
  UavModel model_;
  MpcTracker mpc_;
  Trajectory trajectory_;
  TrackerMode mode_ = TrackerMode::kHolding;
  Eigen::Vector3d hold_p_W_ = Eigen::Vector3d::Zero();
  double hold_yaw_ = 0.0;
  UavCommand command_;        // applied during the last step
  UavCommand mpc_command_;    // the MPC's output, held over the control period
  MpcResult last_solve_;
  std::string last_refusal_;
  int64_t steps_ = 0;
  int64_t steps_per_control_ = 1;
  int64_t next_control_step_ = 0;
};

}  // namespace surface_nbv
