// Angle helpers shared by the planning, tracking and ROS code.
#pragma once

#include <cmath>

namespace surface_nbv {

// An angle in radians wrapped to (-pi, pi]; a non-finite one gives 0.
inline double wrapAngle(double angle) {
  if (!std::isfinite(angle)) return 0.0;
  double w = std::remainder(angle, 2.0 * M_PI);  // [-pi, pi]
  if (w <= -M_PI) w += 2.0 * M_PI;
  return w;
}

}  // namespace surface_nbv
