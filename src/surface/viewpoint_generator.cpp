#include "surface_nbv/surface/viewpoint_generator.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

double wrapAngle(double a) { return std::remainder(a, 2.0 * M_PI); }

Eigen::Vector3d fromAngles(double azimuth, double elevation) {
  return Eigen::Vector3d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                         std::sin(elevation));
}

}  // namespace

ViewpointGenerator::ViewpointGenerator(const SurfaceConfig& config) : config_(config) {
  max_elevation_ = (0.5 * config_.camera.vfov_deg - config_.fov_margin_deg) * kDegToRad;
  for (double a : config_.fallback_rotations_deg) rotations_.push_back(a * kDegToRad);
  int n = 0;
  for (int dz = -1; dz <= 1; ++dz) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        neighbours_[n] = Eigen::Vector3i(dx, dy, dz);
        offsets_[n] = Eigen::Vector3d(dx, dy, dz).normalized();
        ++n;
      }
    }
  }
}

Eigen::Vector3d ViewpointGenerator::direction(const VoxelStateGrid& grid, const Eigen::Vector3i& voxel) const {
  // Sum of w'(c) (c - v) / |c - v| with w' = -1 for occupied, +1 otherwise
  // (the paper's +-W_th, scaled). Since the 26 unit offsets sum to zero, this
  // is -2 times the sum over the occupied neighbours: only those are added.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < 26; ++i) {
    if (grid.at(voxel + neighbours_[i]) == VoxelStateGrid::kOccupied) sum -= offsets_[i];
  }
  const double norm = sum.norm();
  return norm > 1e-9 ? Eigen::Vector3d(sum / norm) : Eigen::Vector3d::Zero();
}

std::vector<Eigen::Vector3d> ViewpointGenerator::candidateDirections(const Eigen::Vector3d& n_v) const {
  std::vector<Eigen::Vector2d> angles;  // (azimuth, elevation), before clamping
  const double horizontal = std::hypot(n_v.x(), n_v.y());
  const double elevation = std::atan2(n_v.z(), horizontal);
  std::vector<double> bases;
  if (horizontal > 1e-6) {
    bases.push_back(std::atan2(n_v.y(), n_v.x()));
  } else {
    for (int k = 0; k < 8; ++k) bases.push_back(k * M_PI / 4.0);
  }
  for (double az : bases) angles.emplace_back(az, elevation);
  for (double a : rotations_) {
    for (double az : bases) {
      angles.emplace_back(az + a, elevation);
      angles.emplace_back(az - a, elevation);
      angles.emplace_back(az, elevation + a);
      angles.emplace_back(az, elevation - a);
    }
  }
  std::vector<Eigen::Vector2d> kept;
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector2d& ae : angles) {
    // Elevation beyond +-90 degrees comes back on the other side.
    double az = ae.x(), el = ae.y();
    if (el > M_PI / 2) el = M_PI - el, az += M_PI;
    if (el < -M_PI / 2) el = -M_PI - el, az += M_PI;
    const Eigen::Vector2d c(wrapAngle(az), std::clamp(el, -max_elevation_, max_elevation_));
    const bool seen = std::any_of(kept.begin(), kept.end(), [&](const Eigen::Vector2d& k) {
      return std::abs(wrapAngle(k.x() - c.x())) < 1e-9 && std::abs(k.y() - c.y()) < 1e-9;
    });
    if (seen) continue;
    kept.push_back(c);
    out.push_back(fromAngles(c.x(), c.y()));
  }
  return out;
}

std::vector<double> ViewpointGenerator::candidateDistances(double elevation) const {
  // The ISE's depth is the horizontal distance d cos(elevation).
  const double closest = config_.camera.min_range / std::cos(elevation) + 1e-6;
  std::vector<double> out;
  if (config_.delta_pose >= closest) out.push_back(config_.delta_pose);
  for (double f : config_.fallback_distance_fractions) {
    const double d = f * config_.delta_pose;
    if (d >= closest && (out.empty() || d < out.back() - 1e-9)) out.push_back(d);
  }
  if (out.empty() || closest < out.back() - 1e-9) out.push_back(closest);
  return out;
}

bool ViewpointGenerator::acceptable(const VoxelRayCaster& rays, const CollisionMap& collision,
                                    const AlignedBox& bounds, const Eigen::Vector3i& voxel,
                                    const Eigen::Vector3d& p_W) const {
  if (!bounds.contains(p_W) || !collision.isFree(p_W, config_.collision_radius)) return false;
  const Eigen::Vector3d d = rays.grid().voxelCenter(voxel) - p_W;
  const double depth = std::hypot(d.x(), d.y());
  if (depth < config_.camera.min_range || depth > config_.camera.max_range) return false;
  if (std::abs(std::atan2(d.z(), depth)) > max_elevation_ + 1e-9) return false;
  uint64_t steps = 0;
  return rays.clear(p_W, voxel, &steps);
}

PoseSearch ViewpointGenerator::generate(const VoxelRayCaster& rays, const CollisionMap& collision,
                                        const AlignedBox& bounds, const Eigen::Vector3i& voxel,
                                        const Eigen::Vector3d& n_v, Viewpoint* pose) const {
  PoseSearch search;
  if (n_v.squaredNorm() < 0.5) return search;
  const VoxelStateGrid& grid = rays.grid();
  const Eigen::Vector3d v = grid.voxelCenter(voxel);
  for (const Eigen::Vector3d& dir : candidateDirections(n_v)) {
    for (double d : candidateDistances(std::asin(std::clamp(dir.z(), -1.0, 1.0)))) {
      ++search.tested;
      const Eigen::Vector3d p = v + d * dir;
      if (!acceptable(rays, collision, bounds, voxel, p)) {
        Eigen::Vector3i at;
        if (grid.voxelOf(p, &at) && grid.at(at) == VoxelStateGrid::kUnknown) search.unknown_blocked = true;
        continue;
      }
      pose->position = p;
      pose->view_direction = -dir;
      pose->yaw = std::atan2(-dir.y(), -dir.x());
      search.found = true;
      return search;
    }
  }
  return search;
}

}  // namespace surface_nbv
