#include "surface_nbv/tracking/trajectory.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "surface_nbv/tracking/uav_model.h"

namespace surface_nbv {

Status Trajectory::validate(const Eigen::Vector3d& p_W, double max_start_distance) const {
  if (points_.empty()) return Status::Error("trajectory is empty");
  for (size_t i = 0; i < points_.size(); ++i) {
    const TrajectoryPoint& q = points_[i];
    const std::string where = "trajectory point " + std::to_string(i);
    if (!std::isfinite(q.t) || !q.p_W.allFinite() || !std::isfinite(q.yaw) ||
        (q.has_velocity && !q.v_W.allFinite())) {
      return Status::Error(where + " has a NaN or infinite value");
    }
    if (q.p_W.cwiseAbs().maxCoeff() > kMaxCoordinate || std::abs(q.t) > 1e9 ||
        (q.has_velocity && q.v_W.cwiseAbs().maxCoeff() > kMaxCoordinate)) {
      return Status::Error(where + " has a coordinate, velocity or time beyond 1e6 m, 1e6 m/s or 1e9 s");
    }
    if (i > 0 && !(q.t > points_[i - 1].t)) {
      return Status::Error(where + " time " + std::to_string(q.t) + " s is not after the previous point's " +
                           std::to_string(points_[i - 1].t) + " s (times must increase strictly)");
    }
  }
  if (!p_W.allFinite()) return Status::Error("current position is not finite");
  const double distance = (points_.front().p_W - p_W).norm();
  if (!(distance <= max_start_distance)) {
    return Status::Error("trajectory starts " + std::to_string(distance) + " m from the UAV (limit " +
                         std::to_string(max_start_distance) + " m)");
  }
  return Status::Ok();
}

TrajectorySample Trajectory::sample(double t) const {
  TrajectorySample s;
  if (points_.empty()) return s;
  if (!(t > points_.front().t) || points_.size() == 1) {
    s.p_W = points_.front().p_W;
    s.yaw = wrapAngle(points_.front().yaw);
    return s;
  }
  if (t >= points_.back().t) {
    s.p_W = points_.back().p_W;
    s.yaw = wrapAngle(points_.back().yaw);
    return s;
  }
  const auto after = std::upper_bound(points_.begin(), points_.end(), t,
                                      [](double time, const TrajectoryPoint& q) { return time < q.t; });
  const TrajectoryPoint& b = *after;
  const TrajectoryPoint& a = *(after - 1);
  const double span = b.t - a.t;
  const double f = (t - a.t) / span;
  s.p_W = a.p_W + f * (b.p_W - a.p_W);
  s.v_W = a.has_velocity && b.has_velocity ? Eigen::Vector3d(a.v_W + f * (b.v_W - a.v_W))
                                           : Eigen::Vector3d((b.p_W - a.p_W) / span);
  s.yaw = wrapAngle(a.yaw + f * wrapAngle(b.yaw - a.yaw));
  return s;
}

void Trajectory::shiftTimes(double dt) {
  for (TrajectoryPoint& q : points_) q.t += dt;
}

Trajectory timeWaypoints(const std::vector<Waypoint>& waypoints, double start_time, double speed,
                         double yaw_rate) {
  std::vector<TrajectoryPoint> points;
  if (waypoints.empty() || !(speed > 0.0) || !(yaw_rate > 0.0)) return Trajectory(points);
  TrajectoryPoint first;
  first.t = start_time;
  first.p_W = waypoints.front().p_W;
  first.yaw = waypoints.front().yaw;
  points.push_back(first);
  for (size_t i = 1; i < waypoints.size(); ++i) {
    const TrajectoryPoint& last = points.back();
    const double length = (waypoints[i].p_W - last.p_W).norm();
    const double turn = std::abs(wrapAngle(waypoints[i].yaw - last.yaw));
    const double duration = std::max(length / speed, turn / yaw_rate);
    if (!(duration > 1e-9)) continue;
    TrajectoryPoint q;
    q.t = last.t + duration;
    q.p_W = waypoints[i].p_W;
    q.yaw = waypoints[i].yaw;
    points.push_back(q);
  }
  return Trajectory(std::move(points));
}

}  // namespace surface_nbv
