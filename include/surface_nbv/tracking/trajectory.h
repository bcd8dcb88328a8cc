// A time-stamped reference for the tracker, the ROS-free image of a
// trajectory_msgs/MultiDOFJointTrajectory: points with an absolute time (s, on
// the tracker's clock), a position and yaw in the world frame, an optional
// velocity. Linear interpolation between points; immutable once built.
#pragma once

#include <vector>

#include "surface_nbv/common.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct TrajectoryPoint {
  double t = 0.0;                                 // s, absolute
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  double yaw = 0.0;                               // rad
  bool has_velocity = false;
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();  // used when has_velocity
};

struct TrajectorySample {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_W = Eigen::Vector3d::Zero();
  double yaw = 0.0;
};

class Trajectory {
 public:
  // Points beyond this many metres from the origin are refused (keeps the
  // solver's arithmetic far from overflow).
  static constexpr double kMaxCoordinate = 1e6;

  Trajectory() = default;
  explicit Trajectory(std::vector<TrajectoryPoint> points) : points_(std::move(points)) {}

  // Refuses, with a reason naming the point: no points, a non-finite or huge
  // value, times not strictly increasing, a first point farther than
  // max_start_distance (m) from p_W (the current position).
  Status validate(const Eigen::Vector3d& p_W, double max_start_distance) const;

  // The reference at time t: before the start the first point, after the end
  // the last point, both at rest; in between positions and given velocities are
  // interpolated linearly (without given velocities, the segment's mean
  // velocity), yaw along the shorter arc. Precondition: validate() passed.
  TrajectorySample sample(double t) const;

  bool empty() const { return points_.empty(); }
  size_t size() const { return points_.size(); }
  double startTime() const { return points_.empty() ? 0.0 : points_.front().t; }
  double endTime() const { return points_.empty() ? 0.0 : points_.back().t; }
  const std::vector<TrajectoryPoint>& points() const { return points_; }
  // Adds dt seconds to every time (e.g. relative times -> the tracker's clock).
  void shiftTimes(double dt);

 private:
  std::vector<TrajectoryPoint> points_;
};

// A waypoint for timeWaypoints(): position and yaw.
struct Waypoint {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  double yaw = 0.0;
};

// Times a polyline of waypoints at a constant translational speed (m/s, the
// paper's 0.5 by default) from start_time; a segment lasts at least the time
// its yaw change takes at yaw_rate (rad/s), so pure rotations get time too.
// Velocities are left unset (each segment's mean velocity is used). Repeated
// waypoints are skipped.
Trajectory timeWaypoints(const std::vector<Waypoint>& waypoints, double start_time, double speed = 0.5,
                         double yaw_rate = 0.5);

}  // namespace surface_nbv
