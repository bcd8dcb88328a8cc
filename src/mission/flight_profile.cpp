#include "surface_nbv/mission/flight_profile.h"

#include <algorithm>
#include <cmath>

#include "surface_nbv/util/angles.h"

namespace surface_nbv {

FlightProfile profileFlight(const std::vector<Eigen::Vector4d>& poses, const std::vector<double>& times,
                            double reference_speed, double slow_speed, double cruise_fraction, double turn_rate) {
  FlightProfile profile;
  const size_t n = std::min(poses.size(), times.size());
  const double cruise_speed = cruise_fraction * reference_speed;
  for (size_t i = 1; i < n; ++i) {
    const double dt = times[i] - times[i - 1];
    if (!std::isfinite(dt) || dt <= 0.0 || !poses[i - 1].allFinite() || !poses[i].allFinite()) continue;
    const Eigen::Vector3d step = poses[i].head<3>() - poses[i - 1].head<3>();
    const double distance = step.norm();
    const double yaw_change = std::abs(wrapAngle(poses[i].w() - poses[i - 1].w()));
    const double speed = distance / dt;
    ++profile.samples;
    profile.flight_s += dt;
    profile.path_m += distance;
    profile.total_yaw_rad += yaw_change;
    if (speed < slow_speed) {
      (yaw_change / dt > turn_rate ? profile.turning_in_place_s : profile.stopped_s) += dt;
      continue;
    }
    (speed >= cruise_speed ? profile.cruise_s : profile.moving_s) += dt;
    if (std::abs(step.z()) > step.head<2>().norm()) profile.vertical_s += dt;
  }
  return profile;
}

}  // namespace surface_nbv
