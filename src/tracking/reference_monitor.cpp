#include "surface_nbv/tracking/reference_monitor.h"

#include <algorithm>

namespace surface_nbv {

void ReferenceMonitor::setReference(std::vector<std::pair<double, Eigen::Vector3d>> points) {
  points_ = std::move(points);
  off_ = false;
}

double ReferenceMonitor::error(double t, const Eigen::Vector3d& p) const {
  if (points_.empty()) return 0.0;
  Eigen::Vector3d reference = points_.back().second;
  for (size_t i = 1; i < points_.size(); ++i) {
    if (t >= points_[i].first) continue;
    const double t0 = points_[i - 1].first, t1 = points_[i].first;
    const double f = t <= t0 ? 0.0 : (t - t0) / std::max(t1 - t0, 1e-9);
    reference = points_[i - 1].second + f * (points_[i].second - points_[i - 1].second);
    break;
  }
  return (p - reference).norm();
}

bool ReferenceMonitor::offTrack(double t, const Eigen::Vector3d& p, double* error) {
  *error = max_error_ > 0.0 ? this->error(t, p) : 0.0;
  if (max_error_ <= 0.0 || *error <= max_error_) {
    off_ = false;
    return false;
  }
  if (!off_) off_since_ = t;
  off_ = true;
  return t - off_since_ >= hold_time_;
}

}  // namespace surface_nbv
