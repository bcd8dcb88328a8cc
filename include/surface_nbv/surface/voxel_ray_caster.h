// Line of sight through a VoxelStateGrid by the 3D DDA of Amanatides and Woo
// (1987): from a point to the centre of a target voxel, every voxel the
// segment crosses is entered once, 6-connected, in order. A ray is blocked by
// an occupied voxel and, when unknown_blocks, by an unknown one; the voxel of
// the start point and the target voxel are not tested. The walk keeps one
// linear index into the padded grid and fixed-point crossing parameters, and
// picks the axis of the next crossing with masks instead of branches, so a
// step is a handful of integer operations. Thread safety: const methods,
// safe from many threads while the grid is not refreshed.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include <Eigen/Core>

#include "surface_nbv/surface/voxel_state_grid.h"

namespace surface_nbv {

class VoxelRayCaster {
 public:
  VoxelRayCaster(const VoxelStateGrid& grid, bool unknown_blocks)
      : grid_(grid),
        mask_(static_cast<uint8_t>(VoxelStateGrid::kOccupied | (unknown_blocks ? VoxelStateGrid::kUnknown : 0))) {}

  // True when nothing blocks the segment from p_W to the centre of `target`.
  // False when p_W is outside the voxel grid or `target` is. Adds the voxels
  // entered (the blocking one included, the target excluded) to *steps.
  bool clear(const Eigen::Vector3d& p_W, const Eigen::Vector3i& target, uint64_t* steps) const {
    return walk(p_W, target, steps, [this](size_t i) { return (grid_.data()[i] & mask_) == 0; });
  }

  // Calls visit(linear grid index) for each voxel entered strictly between
  // the start voxel and `target`, in order, until it returns false; returns
  // whether the walk reached the target. For tests and tools.
  template <typename Visit>
  bool walk(const Eigen::Vector3d& p_W, const Eigen::Vector3i& target, uint64_t* steps, Visit&& visit) const {
    const Eigen::Vector3d o = (p_W - grid_.origin()) / grid_.voxelSize();
    if (!o.allFinite() || !grid_.voxelInGrid(target)) return false;
    const Eigen::Vector3i start = o.array().floor().cast<int>();
    if (!grid_.voxelInGrid(start)) return false;
    // The ray parameter t runs from 0 (p_W) to 1 (the target's centre), in
    // fixed point (kOne = 1) so that a step is integer compares and adds.
    const int64_t strides[3] = {1, grid_.strideY(), grid_.strideZ()};
    int64_t t_max[3], t_delta[3], step[3];
    int remaining = 0;
    for (int a = 0; a < 3; ++a) {
      const int n = target[a] - start[a];
      const double d = target[a] + 0.5 - o[a];  // |d| >= 0.5 when n != 0
      remaining += std::abs(n);
      if (n == 0) {
        t_max[a] = kNever;
        t_delta[a] = 0;
        step[a] = 0;
      } else {
        const double boundary = n > 0 ? start[a] + 1 - o[a] : start[a] - o[a];
        t_max[a] = static_cast<int64_t>(std::llround(boundary / d * kOne));
        t_delta[a] = static_cast<int64_t>(std::llround(std::abs(1.0 / d) * kOne));
        step[a] = n > 0 ? strides[a] : -strides[a];
      }
    }
    // Every crossing on an axis that still has to move comes before t = 1
    // (the target centre) and every further one at least 0.5 / |d| after it,
    // so the smallest t_max always belongs to an axis that must still step:
    // `remaining` steps end exactly in the target. The axis is picked with
    // masks, not branches, so the loop does not stall on mispredictions.
    int64_t tx = t_max[0], ty = t_max[1], tz = t_max[2];
    const int64_t dx = t_delta[0], dy = t_delta[1], dz = t_delta[2];
    const int64_t sx = step[0], sy = step[1], sz = step[2];
    size_t index = grid_.index(start);
    for (int k = 1; k < remaining; ++k) {
      const int64_t mx = -static_cast<int64_t>((tx <= ty) & (tx <= tz));
      const int64_t my = ~mx & -static_cast<int64_t>(ty <= tz);
      const int64_t mz = ~(mx | my);
      index += static_cast<size_t>((sx & mx) | (sy & my) | (sz & mz));
      tx += dx & mx;
      ty += dy & my;
      tz += dz & mz;
      if (!visit(index)) {
        *steps += static_cast<uint64_t>(k);
        return false;
      }
    }
    *steps += static_cast<uint64_t>(remaining > 0 ? remaining - 1 : 0);
    return true;
  }

  const VoxelStateGrid& grid() const { return grid_; }

 private:
  static constexpr int64_t kOne = int64_t{1} << 40;
  static constexpr int64_t kNever = int64_t{1} << 60;

  const VoxelStateGrid& grid_;
  uint8_t mask_;
};

}  // namespace surface_nbv
