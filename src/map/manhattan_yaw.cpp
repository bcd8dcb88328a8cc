#include "surface_nbv/map/manhattan_yaw.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {
namespace {

// a modulo 90 deg into [-pi/4, pi/4).
double wrapQuarter(double a) {
  const double q = 0.5 * M_PI;
  return a - q * std::floor((a + 0.25 * M_PI) / q);
}

}  // namespace

Status ManhattanYawConfig::validate() const {
  if (grid < 1 || grid > 64) return Status::Error("manhattan_yaw_grid expected in [1, 64] px");
  if (!(baseline > 0.0)) return Status::Error("manhattan_yaw_baseline expected > 0 m");
  if (!(max_depth > 0.0)) return Status::Error("manhattan_yaw_max_depth expected > 0 m");
  if (min_normals < 1) return Status::Error("manhattan_yaw_min_normals expected >= 1");
  if (!(min_significance > 0.0)) return Status::Error("manhattan_yaw_min_significance expected > 0");
  if (!(gain > 0.0 && gain <= 1.0)) return Status::Error("manhattan_yaw_gain expected in (0, 1]");
  if (!(max_error_deg > 0.0 && max_error_deg <= 45.0)) {
    return Status::Error("manhattan_yaw_max_error_deg expected in (0, 45]");
  }
  return Status::Ok();
}

ManhattanYawFrame manhattanDirection(const DepthCamera& camera, const DepthImage& depth, const Transform& T_W_C,
                                     const ManhattanYawConfig& config) {
  ManhattanYawFrame f;
  const int s = config.grid;
  const double fx = camera.fx();
  const double min_z = camera.config().min_range, max_z = std::min(config.max_depth, camera.config().max_range);
  auto point = [&](int row, int col, Eigen::Vector3d* p) {
    const double z = depth.at(row, col);
    if (!(z >= min_z && z <= max_z)) return false;
    *p = camera.pixelRay(col, row) * z;
    return true;
  };
  const double horizontal = std::sin(20.0 * M_PI / 180.0);  // |n_z| below this: a vertical surface
  double c = 0.0, sn = 0.0;
  for (int row = s / 2; row < depth.height; row += s) {
    for (int col = s / 2; col < depth.width; col += s) {
      Eigen::Vector3d p, px, py;
      if (!point(row, col, &p)) continue;
      const int k = std::max(1, static_cast<int>(std::lround(config.baseline * fx / p.z())));
      if (col + k >= depth.width || row + k >= depth.height) continue;
      if (!point(row, col + k, &px) || !point(row + k, col, &py)) continue;
      const Eigen::Vector3d dx = px - p, dy = py - p;
      // One surface: no depth jump between the three points.
      const double reach = 3.0 * config.baseline;
      if (dx.norm() > reach || dy.norm() > reach) continue;
      const Eigen::Vector3d n_W = T_W_C.linear() * dx.cross(dy).normalized();
      if (!n_W.allFinite() || std::abs(n_W.z()) > horizontal) continue;
      const double a = std::atan2(n_W.y(), n_W.x());
      c += std::cos(4.0 * a);
      sn += std::sin(4.0 * a);
      ++f.normals;
    }
  }
  if (f.normals == 0) return f;
  f.concentration = std::hypot(c, sn) / f.normals;
  f.direction = wrapQuarter(0.25 * std::atan2(sn, c));
  f.trusted = f.normals >= config.min_normals && f.concentration * std::sqrt(f.normals) >= config.min_significance;
  return f;
}

double ManhattanYaw::update(const DepthCamera& camera, const DepthImage& depth, const Transform& T_W_C) {
  const ManhattanYawFrame f = manhattanDirection(camera, depth, T_W_C, config_);
  if (!f.trusted) return 0.0;
  if (!has_reference_) {
    has_reference_ = true;
    reference_ = f.direction;
    return 0.0;
  }
  const double error = wrapQuarter(reference_ - f.direction);
  if (std::abs(error) > config_.max_error_deg * M_PI / 180.0) return 0.0;
  ++corrections_;
  return config_.gain * error;
}

}  // namespace surface_nbv
