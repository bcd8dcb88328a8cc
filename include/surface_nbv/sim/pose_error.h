// Imperfect localisation (issue #40): the pose a UAV's odometry (VIO)
// reports is not where it is.
//
// The simulated UAV flies on its estimated pose: the tracker, the planner and
// the mapper all live in the estimate's world, and the camera really is at
//   T_W_C(true) = D * T_W_C(estimate),
// where D (a yaw about z and a translation: gravity keeps roll and pitch
// observable) is the odometry's drift, a random walk per metre flown: each
// step of the estimate by ds metres adds a translation with a standard
// deviation of drift_rate * sqrt(ds * 1 m) per axis and a yaw with
// yaw_drift_deg * sqrt(ds * 1 m), turned about the UAV so that the true
// position moves only by the translation; the motion after it is turned with
// the accumulated yaw, as an odometry with a wrong heading integrates it. So
// after d metres the position error has drift_rate * sqrt(d) (per axis, d in
// metres) from the walk alone: 0.005 ("0.5 %") is 5 mm after 1 m, 5 cm after
// 100 m, 22 cm after 1900 m.
// On top, each frame's pose handed to the mapper has a per-frame jitter:
// T_W_C(reported) = T_W_C(estimate) * J_k, J_k a translation with
// jitter_position per axis and a rotation with jitter_angle_deg about each
// axis. The depth is rendered at the true pose, fused at the reported one,
// and the reconstruction is evaluated against the true scene.
// Every draw is a pure function of (seed, frame index), as the depth noise's
// of (seed, frame, pixel). All zero (the default): no error, and the poses
// are returned untouched.
#pragma once

#include <cstdint>

#include "surface_nbv/common.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct PoseErrorConfig {
  double drift_rate = 0.0;        // position random walk [m per sqrt(m) flown], per axis
  double yaw_drift_deg = 0.0;     // yaw random walk [deg per sqrt(m) flown]
  double jitter_position = 0.0;   // per-frame position jitter [m], per axis
  double jitter_angle_deg = 0.0;  // per-frame attitude jitter [deg], about each axis
  uint64_t seed = 1;              // nbv_mission adds the trial's seed

  bool enabled() const {
    return drift_rate > 0.0 || yaw_drift_deg > 0.0 || jitter_position > 0.0 || jitter_angle_deg > 0.0;
  }
  // Names the first bad key, e.g. "pose_drift_rate expected in [0, 1]".
  Status validate() const;
};

// How far the estimate was from the truth over a flight.
struct PoseErrorStats {
  size_t frames = 0;
  double final_position = 0.0;  // |p_true - p_estimate| at the last frame [m]
  double rms_position = 0.0;    // over the frames [m]
  double max_position = 0.0;    // [m]
  double final_yaw_deg = 0.0;   // |yaw error| at the last frame
  double rms_yaw_deg = 0.0;

  // One frame's position error [m] and yaw error [rad].
  void add(double position, double yaw);
  // Adds the error of pose `T` against the true pose `T_true`.
  void addPose(const Transform& T, const Transform& T_true);

 private:
  double sum_sq_position_ = 0.0, sum_sq_yaw_ = 0.0;
};

class PoseErrorModel {
 public:
  explicit PoseErrorModel(const PoseErrorConfig& config);

  bool enabled() const { return config_.enabled(); }
  const PoseErrorConfig& config() const { return config_; }

  // The estimate is at p_W for `frame` (frame indices increasing): the
  // drift walks by the distance from the previous call's position.
  void advance(const Eigen::Vector3d& p_W, uint64_t frame);
  // The true pose of a pose of the estimate (unchanged when disabled).
  Transform truePose(const Transform& T_estimate) const;
  // The pose `frame` is fused with: the estimate with that frame's jitter
  // (unchanged when disabled).
  Transform reportedPose(const Transform& T_estimate, uint64_t frame) const;
  // The drift: the estimate's world in the true world.
  const Transform& drift() const { return D_; }
  double driftYaw() const { return yaw_; }
  double distance() const { return distance_; }
  const PoseErrorStats& stats() const { return stats_; }

 private:
  PoseErrorConfig config_;
  Transform D_ = Transform::Identity();
  double yaw_ = 0.0;
  double distance_ = 0.0;
  bool started_ = false;
  Eigen::Vector3d last_p_ = Eigen::Vector3d::Zero();
  PoseErrorStats stats_;
};

}  // namespace surface_nbv
