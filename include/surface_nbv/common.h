// Common Eigen typedefs and small helpers shared by every concern.
// Conventions: poses are double (T_W_C maps camera-frame points into the world
// frame), voxel and mesh data are float. Units are metres and radians.
#pragma once

#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace surface_nbv {

using Point3f = Eigen::Vector3f;
using Point3d = Eigen::Vector3d;
using Transform = Eigen::Isometry3d;

// An axis-aligned box. Empty when min > max on any axis.
struct AlignedBox {
  Eigen::Vector3d min{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity())};
  Eigen::Vector3d max{Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};

  AlignedBox() = default;
  AlignedBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) : min(lo), max(hi) {}

  bool empty() const { return (min.array() > max.array()).any(); }
  bool contains(const Eigen::Vector3d& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
  void extend(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  Eigen::Vector3d center() const { return 0.5 * (min + max); }
  Eigen::Vector3d size() const { return max - min; }
};

}  // namespace surface_nbv
