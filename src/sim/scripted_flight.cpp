#include "surface_nbv/sim/scripted_flight.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace surface_nbv {

Status FlightConfig::validate() const {
  if (target.empty() || !target.min.allFinite() || !target.max.allFinite()) {
    return Status::Error("flight target box expected finite and non-empty");
  }
  if (!std::isfinite(standoff) || standoff <= 0.0) return Status::Error("flight/standoff expected > 0");
  if (!std::isfinite(speed) || speed <= 0.0) return Status::Error("flight/speed expected > 0");
  if (altitudes.empty()) return Status::Error("flight/altitudes expected at least one altitude");
  for (double z : altitudes) {
    if (!std::isfinite(z)) return Status::Error("flight/altitudes expected finite values");
  }
  return Status::Ok();
}

FlightConfig flightAround(const AlignedBox& bounds, double standoff, int levels, double speed) {
  FlightConfig config;
  config.target = bounds;
  config.standoff = standoff;
  config.speed = speed;
  config.altitudes.clear();
  levels = std::max(1, levels);
  const double lo = bounds.min.z() + 1.5, hi = bounds.max.z();
  for (int i = 0; i < levels; ++i) config.altitudes.push_back(lo + (hi - lo) * (i + 0.5) / levels);
  return config;
}

ScriptedFlight::ScriptedFlight(const FlightConfig& config) : config_(config) {
  for (size_t i = 0; i < config_.altitudes.size(); ++i) {
    const size_t loop_start = segments_.size();
    addLoop(config_.altitudes[i]);
    if (i == 0) continue;
    // Each loop ends where it starts: climb there from the previous altitude.
    Segment climb;
    climb.end = segments_[loop_start].start;
    climb.start = Eigen::Vector3d(climb.end.x(), climb.end.y(), config_.altitudes[i - 1]);
    climb.yaw0 = climb.yaw1 = segments_[loop_start].yaw0;
    climb.length = std::abs(climb.end.z() - climb.start.z());
    segments_.insert(segments_.begin() + loop_start, climb);
  }
  for (const Segment& s : segments_) total_length_ += s.length;
}

void ScriptedFlight::addLoop(double z) {
  const double x0 = config_.target.min.x(), x1 = config_.target.max.x();
  const double y0 = config_.target.min.y(), y1 = config_.target.max.y();
  const double r = config_.standoff;
  const Eigen::Vector2d corners[4] = {{x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}};
  for (int k = 0; k < 4; ++k) {
    const double a = -M_PI / 2 + k * M_PI / 2;  // outward normal of the side leading into corner k
    const Eigen::Vector2d& prev = corners[(k + 3) % 4];
    const Eigen::Vector2d& c = corners[k];
    const Eigen::Vector2d n(std::cos(a), std::sin(a));
    Segment side;
    side.start = Eigen::Vector3d(prev.x() + r * n.x(), prev.y() + r * n.y(), z);
    side.end = Eigen::Vector3d(c.x() + r * n.x(), c.y() + r * n.y(), z);
    side.yaw0 = side.yaw1 = a + M_PI;
    side.length = (side.end - side.start).norm();
    segments_.push_back(side);
    Segment corner;
    corner.arc = true;
    corner.start = Eigen::Vector3d(c.x(), c.y(), z);
    corner.end = corner.start;
    corner.yaw0 = a + M_PI;
    corner.yaw1 = a + M_PI + M_PI / 2;
    corner.length = r * M_PI / 2;
    segments_.push_back(corner);
  }
}

Transform ScriptedFlight::poseAt(double t) const { return poseAtDistance(t * config_.speed); }

Transform ScriptedFlight::poseAtDistance(double s) const {
  s = std::clamp(s, 0.0, total_length_);
  size_t i = 0;
  while (i + 1 < segments_.size() && s > segments_[i].length) s -= segments_[i++].length;
  const Segment& seg = segments_[i];
  const double f = seg.length > 0.0 ? std::clamp(s / seg.length, 0.0, 1.0) : 0.0;
  const double yaw = seg.yaw0 + f * (seg.yaw1 - seg.yaw0);
  Eigen::Vector3d p;
  if (seg.arc) {
    const double polar = yaw - M_PI;
    p = seg.start + config_.standoff * Eigen::Vector3d(std::cos(polar), std::sin(polar), 0.0);
  } else {
    p = seg.start + f * (seg.end - seg.start);
  }
  return levelBodyPose(p, yaw);
}

}  // namespace surface_nbv
