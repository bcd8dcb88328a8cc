// Eq. 2: the viewing direction n_v of an ISE and the first acceptable pose
// for it. n_v sums the unit offsets to the 26 neighbours, weighted -W_th for
// occupied and +W_th otherwise (W_th drops out once normalised); voxels
// outside the grid count as not occupied. A pose p = v + d * dir is
// acceptable when p lies inside the bounds and is collision-free with the
// configured radius (the CollisionMap: unknown space is an obstacle), and
// the camera yawed to look at v (on a level UAV, its mount's pitch down) has
// v inside its vertical FOV (less the margin) and depth range with a clear line of sight (VoxelRayCaster).
// Candidates in order: dir = n_v with its elevation clamped to the usable
// vertical FOV; then n_v turned by +a and -a in yaw, then in elevation, for
// each fall-back rotation a (from 8 yaws 45 degrees apart when n_v is
// vertical). Along each: d = delta_pose, then its fractions, then the
// distance that puts v at the camera's min range. Const: thread-safe.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/common.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/surface/surface_config.h"
#include "surface_nbv/surface/voxel_ray_caster.h"

namespace surface_nbv {

// What the search for one ISE's pose found.
struct PoseSearch {
  bool found = false;
  int tested = 0;                // candidates tried (1: the eq. 2 pose itself was accepted)
  bool unknown_blocked = false;  // some candidate inside the bounds lay in an unknown voxel
  bool approach = false;         // found only as an approach pose (see SurfaceConfig)
};

class ViewpointGenerator {
 public:
  // `config` must validate(); the constructor trusts it.
  explicit ViewpointGenerator(const SurfaceConfig& config);

  // n_v at `voxel` (unit), zero when the weighted sum vanishes.
  Eigen::Vector3d direction(const VoxelStateGrid& grid, const Eigen::Vector3i& voxel) const;

  // The first acceptable candidate for the ISE at `voxel` with direction
  // `n_v`: when found, fills position, yaw and view_direction of *pose.
  // Not found when no candidate is acceptable or n_v is zero (the ISE
  // belongs to C_rem).
  // `loose`, when given, is a ray caster through unknown space over the same
  // grid: with it, an unknown-blocked search goes on with approach poses.
  PoseSearch generate(const VoxelRayCaster& rays, const CollisionMap& collision, const AlignedBox& bounds,
                      const Eigen::Vector3i& voxel, const Eigen::Vector3d& n_v, Viewpoint* pose,
                      const VoxelRayCaster* loose = nullptr) const;

  // Whether a camera at p_W, yawed towards `voxel`, is an acceptable pose for it.
  bool acceptable(const VoxelRayCaster& rays, const CollisionMap& collision, const AlignedBox& bounds,
                  const Eigen::Vector3i& voxel, const Eigen::Vector3d& p_W) const;

  // Candidate directions (unit, from the ISE towards the pose) for n_v, in order.
  std::vector<Eigen::Vector3d> candidateDirections(const Eigen::Vector3d& n_v) const;
  // Candidate distances along a direction of elevation `elevation` [rad], in order.
  std::vector<double> candidateDistances(double elevation) const;
  // The farthest a candidate pose lies from its ISE [m]: delta_pose, or the
  // approach range when approach poses are on.
  double maxDistance() const {
    return approach_distances_.empty() ? distances_.front() : std::max(distances_.front(), approach_distances_.back());
  }
  // Cosine of the angle between the optical axis of the camera at v + d dir,
  // yawed towards v, and the line back to v: the ISE's depth is d times it.
  double axisCos(const Eigen::Vector3d& dir) const;

 private:
  // The direction with this azimuth and the elevation clamped to the usable FOV.
  Eigen::Vector3d clampedDirection(double azimuth, double elevation) const;
  Eigen::Vector3d clampedDirection(const Eigen::Vector3d& n_v) const;
  // Calls fn(d) for the candidate distances along a direction whose
  // axisCos() is axis_cos, in order, until fn returns true; returns whether
  // it did. The last puts the ISE at the camera's min range.
  template <typename Fn>
  bool forEachDistance(double axis_cos, Fn&& fn) const {
    const double closest = config_.camera.min_range / axis_cos + 1e-6;
    double last = std::numeric_limits<double>::infinity();
    for (double d : distances_) {
      if (d < closest) break;
      if (fn(d)) return true;
      last = d;
    }
    return closest < last - 1e-9 && fn(closest);
  }

  SurfaceConfig config_;
  double pitch_;                  // rad, the mount's pitch down
  double min_elevation_, max_elevation_;  // rad, elevations of a usable direction (ISE to pose)
  std::vector<double> rotations_; // rad
  std::vector<double> distances_; // delta_pose and its fractions, descending
  std::vector<double> approach_distances_;  // beyond delta_pose up to the approach range, ascending
  Eigen::Vector3d offsets_[26];   // unit offsets to the 26 neighbours
  Eigen::Vector3i neighbours_[26];
};

}  // namespace surface_nbv
