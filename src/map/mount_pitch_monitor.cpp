#include "surface_nbv/map/mount_pitch_monitor.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace surface_nbv {

double MountPitchMonitor::axisPitchDeg(const Transform& T_W_C) {
  const Eigen::Vector3d forward = T_W_C.linear().col(2).normalized();
  return std::asin(std::clamp(-forward.z(), -1.0, 1.0)) * 180.0 / M_PI;
}

void MountPitchMonitor::add(const Transform& T_W_C) {
  const double pitch = axisPitchDeg(T_W_C);
  if (!std::isfinite(pitch)) return;
  sum_deg_ += pitch;
  ++frames_;
}

double MountPitchMonitor::meanPitchDeg() const {
  return frames_ == 0 ? std::numeric_limits<double>::quiet_NaN() : sum_deg_ / static_cast<double>(frames_);
}

bool MountPitchMonitor::mismatch(double pitch_deg, double tolerance_deg, size_t min_frames) const {
  return frames_ >= std::max<size_t>(min_frames, 1) && std::abs(meanPitchDeg() - pitch_deg) > tolerance_deg;
}

}  // namespace surface_nbv
