// Whether the UAV follows the reference it was sent (nbv_planner's
// max_tracking_error / off_track_time): the distance from the UAV to the
// reference point of the moment (linear between the timed points, the last
// point after its time), and whether it has stayed farther than max_error
// for hold_time seconds, e.g. a tracker that refused or lost the leg.
// ROS-free; times are seconds since the reference was sent.
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

namespace surface_nbv {

class ReferenceMonitor {
 public:
  // max_error <= 0: the check is off (never off track).
  ReferenceMonitor(double max_error, double hold_time) : max_error_(max_error), hold_time_(hold_time) {}

  // A new reference: (time from its start [s], position) per point, times ascending.
  void setReference(std::vector<std::pair<double, Eigen::Vector3d>> points);
  // Metres from `p` to the reference at `t`; 0 without a reference.
  double error(double t, const Eigen::Vector3d& p) const;
  // Whether `p` at `t` has been off the reference for hold_time (t ascending
  // between calls); `error` gets error(t, p), 0 with the check off.
  bool offTrack(double t, const Eigen::Vector3d& p, double* error);

 private:
  double max_error_, hold_time_;
  std::vector<std::pair<double, Eigen::Vector3d>> points_;
  bool off_ = false;
  double off_since_ = 0.0;
};

}  // namespace surface_nbv
