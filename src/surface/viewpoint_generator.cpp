#include "surface_nbv/surface/viewpoint_generator.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
// Below this horizontal length n_v has no azimuth: it is treated as vertical.
constexpr double kMinHorizontal = 1e-6;

Eigen::Vector3d fromAngles(double azimuth, double elevation) {
  return Eigen::Vector3d(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                         std::sin(elevation));
}

}  // namespace

ViewpointGenerator::ViewpointGenerator(const SurfaceConfig& config) : config_(config) {
  pitch_ = config_.camera.pitch_deg * kDegToRad;
  max_elevation_ = config_.camera.maxPoseElevationDeg(config_.fov_margin_deg) * kDegToRad;
  min_elevation_ = config_.camera.minPoseElevationDeg(config_.fov_margin_deg) * kDegToRad;
  for (double a : config_.fallback_rotations_deg) rotations_.push_back(a * kDegToRad);
  distances_.push_back(config_.delta_pose);
  std::vector<double> fractions = config_.fallback_distance_fractions;
  std::sort(fractions.rbegin(), fractions.rend());
  for (double f : fractions) {
    if (f * config_.delta_pose < distances_.back() - 1e-9) distances_.push_back(f * config_.delta_pose);
  }
  const double approach_max = config_.approach_range_fraction * config_.camera.max_range;
  const double step = 0.25 * config_.delta_pose;
  for (double d = config_.delta_pose + step; d <= approach_max + 1e-9; d += step) approach_distances_.push_back(d);
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

double ViewpointGenerator::axisCos(const Eigen::Vector3d& dir) const {
  return std::cos(std::atan2(dir.z(), std::hypot(dir.x(), dir.y())) - pitch_);
}

Eigen::Vector3d ViewpointGenerator::clampedDirection(double azimuth, double elevation) const {
  return fromAngles(azimuth, std::clamp(elevation, min_elevation_, max_elevation_));
}

Eigen::Vector3d ViewpointGenerator::clampedDirection(const Eigen::Vector3d& n_v) const {
  return clampedDirection(std::atan2(n_v.y(), n_v.x()), std::atan2(n_v.z(), std::hypot(n_v.x(), n_v.y())));
}

std::vector<Eigen::Vector3d> ViewpointGenerator::candidateDirections(const Eigen::Vector3d& n_v) const {
  std::vector<Eigen::Vector2d> angles;  // (azimuth, elevation), before clamping
  const double horizontal = std::hypot(n_v.x(), n_v.y());
  const double elevation = std::atan2(n_v.z(), horizontal);
  std::vector<double> bases;
  if (horizontal > kMinHorizontal) {
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
  std::vector<Eigen::Vector3d> out;
  out.reserve(angles.size());
  for (const Eigen::Vector2d& ae : angles) {
    // Elevation beyond +-90 degrees comes back on the other side.
    double az = ae.x(), el = ae.y();
    if (el > M_PI / 2) el = M_PI - el, az += M_PI;
    if (el < -M_PI / 2) el = -M_PI - el, az += M_PI;
    const Eigen::Vector3d dir = clampedDirection(az, el);
    const bool seen = std::any_of(out.begin(), out.end(), [&](const Eigen::Vector3d& k) {
      return (k - dir).squaredNorm() < 1e-16;
    });
    if (!seen) out.push_back(dir);
  }
  return out;
}

std::vector<double> ViewpointGenerator::candidateDistances(double elevation) const {
  std::vector<double> out;
  forEachDistance(std::cos(elevation - pitch_), [&](double d) {
    out.push_back(d);
    return false;
  });
  return out;
}

bool ViewpointGenerator::acceptable(const VoxelRayCaster& rays, const CollisionMap& collision,
                                    const AlignedBox& bounds, const Eigen::Vector3i& voxel,
                                    const Eigen::Vector3d& p_W) const {
  // A pose in an unknown or occupied voxel fails before the distance query.
  Eigen::Vector3i at;
  if (!bounds.contains(p_W) || !rays.grid().voxelOf(p_W, &at) || rays.grid().at(at) != VoxelStateGrid::kFree ||
      !collision.isFree(p_W, config_.collision_radius)) {
    return false;
  }
  const Eigen::Vector3d d = rays.grid().voxelCenter(voxel) - p_W;
  const double horizontal = std::hypot(d.x(), d.y());
  // Depth along the optical axis of the camera yawed towards the ISE.
  const double depth = std::cos(pitch_) * horizontal - std::sin(pitch_) * d.z();
  if (depth < config_.camera.min_range || depth > config_.camera.max_range) return false;
  const double elevation = -std::atan2(d.z(), horizontal);  // of the pose above the ISE
  if (elevation > max_elevation_ + 1e-9 || elevation < min_elevation_ - 1e-9) return false;
  uint64_t steps = 0;
  return rays.clear(p_W, voxel, &steps);
}

PoseSearch ViewpointGenerator::generate(const VoxelRayCaster& rays, const CollisionMap& collision,
                                        const AlignedBox& bounds, const Eigen::Vector3i& voxel,
                                        const Eigen::Vector3d& n_v, Viewpoint* pose,
                                        const VoxelRayCaster* loose) const {
  PoseSearch search;
  if (n_v.squaredNorm() < 0.5) return search;
  const VoxelStateGrid& grid = rays.grid();
  const Eigen::Vector3d v = grid.voxelCenter(voxel);
  auto setPose = [&](double d, const Eigen::Vector3d& dir) {
    pose->position = v + d * dir;
    pose->view_direction = -dir;
    pose->yaw = std::atan2(-dir.y(), -dir.x());
    search.found = true;
  };
  auto tryDirection = [&](const Eigen::Vector3d& dir) {
    double accepted = 0.0;
    const bool found = forEachDistance(axisCos(dir), [&](double d) {
      ++search.tested;
      const Eigen::Vector3d p = v + d * dir;
      if (acceptable(rays, collision, bounds, voxel, p)) {
        accepted = d;
        return true;
      }
      Eigen::Vector3i at;
      if (grid.voxelOf(p, &at) && grid.at(at) == VoxelStateGrid::kUnknown) search.unknown_blocked = true;
      return false;
    });
    if (found) setPose(accepted, dir);
    return found;
  };
  // Approach poses: the usual distances, then farther ones, with the loose rays.
  auto tryApproach = [&](const Eigen::Vector3d& dir) {
    double accepted = 0.0;
    bool found = forEachDistance(axisCos(dir), [&](double d) {
      ++search.tested;
      accepted = d;
      return acceptable(*loose, collision, bounds, voxel, v + d * dir);
    });
    for (size_t k = 0; !found && k < approach_distances_.size(); ++k) {
      ++search.tested;
      accepted = approach_distances_[k];
      found = acceptable(*loose, collision, bounds, voxel, v + accepted * dir);
    }
    if (found) {
      setPose(accepted, dir);
      search.approach = true;
    }
    return found;
  };
  // Most ISEs need no fall-back: try n_v before listing the other directions.
  const bool has_azimuth = std::hypot(n_v.x(), n_v.y()) > kMinHorizontal;
  if (has_azimuth && tryDirection(clampedDirection(n_v))) return search;
  const std::vector<Eigen::Vector3d> directions = candidateDirections(n_v);
  for (size_t k = has_azimuth ? 1 : 0; k < directions.size(); ++k) {
    if (tryDirection(directions[k])) return search;
  }
  if (loose == nullptr || !search.unknown_blocked || config_.approach_range_fraction <= 0.0) return search;
  for (const Eigen::Vector3d& dir : directions) {
    if (tryApproach(dir)) return search;
  }
  return search;
}

}  // namespace surface_nbv
