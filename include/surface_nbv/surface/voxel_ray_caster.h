// Line of sight through a VoxelStateGrid by the 3D DDA of Amanatides and Woo
// (1987): between a point and the centre of a target voxel, every voxel the
// segment crosses is entered once, 6-connected, in order (exact for points
// off voxel boundaries; on one, a tie may pick a neighbour). A ray is blocked by
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

  // A ray start, prepared once for many rays from the same point.
  struct Origin {
    Eigen::Vector3d o = Eigen::Vector3d::Zero();  // in voxel units from the grid origin
    Eigen::Vector3i voxel = Eigen::Vector3i::Zero();
    size_t index = 0;
    bool valid = false;                            // inside the voxel grid
  };
  Origin origin(const Eigen::Vector3d& p_W) const {
    Origin out;
    out.o = (p_W - grid_.origin()) / grid_.voxelSize();
    if (!out.o.allFinite()) return out;
    out.voxel = out.o.array().floor().cast<int>();
    out.valid = grid_.voxelInGrid(out.voxel);
    if (out.valid) out.index = grid_.index(out.voxel);
    return out;
  }

  // True when nothing blocks the segment from p_W to the centre of `target`.
  // False when p_W is outside the voxel grid or `target` is. The walk goes
  // from the target towards p_W (the same voxels as the other way): a ray
  // blocked next to its target, as rays to an ISE from its unknown or
  // occupied side are, stops at once. Adds the voxels entered (the blocking
  // one included, the end voxel excluded) to *steps.
  bool clear(const Eigen::Vector3d& p_W, const Eigen::Vector3i& target, uint64_t* steps) const {
    return clear(origin(p_W), target, steps);
  }
  bool clear(const Origin& from, const Eigen::Vector3i& target, uint64_t* steps) const {
    return walkBack(from, target, steps, [this](size_t i) { return (grid_.data()[i] & mask_) == 0; });
  }

  // Calls visit(linear grid index) for each voxel entered strictly between
  // the start voxel and `target`, in order from the start, until it returns
  // false; returns whether the walk reached the target.
  template <typename Visit>
  bool walk(const Eigen::Vector3d& p_W, const Eigen::Vector3i& target, uint64_t* steps, Visit&& visit) const {
    const Origin from = origin(p_W);
    if (!from.valid || !grid_.voxelInGrid(target)) return false;
    return walkSegment(from.o, from.voxel, from.index, target.cast<double>().array() + 0.5, target, steps, visit);
  }
  // The same voxels in the opposite order, from `target` towards the start.
  template <typename Visit>
  bool walkBack(const Origin& from, const Eigen::Vector3i& target, uint64_t* steps, Visit&& visit) const {
    if (!from.valid || !grid_.voxelInGrid(target)) return false;
    return walkSegment(target.cast<double>().array() + 0.5, target, grid_.index(target), from.o, from.voxel, steps,
                       visit);
  }

  const VoxelStateGrid& grid() const { return grid_; }

 private:
  // The DDA from point a (voxel units) in voxel `start` (at `index`) to
  // point b in voxel `end`. The parameter t runs from 0 at a to 1 at b, in
  // fixed point (kOne = 1), so a step is integer compares and adds.
  template <typename Visit>
  bool walkSegment(const Eigen::Vector3d& a, const Eigen::Vector3i& start, size_t index, const Eigen::Vector3d& b,
                   const Eigen::Vector3i& end, uint64_t* steps, Visit& visit) const {
    const int64_t strides[3] = {1, grid_.strideY(), grid_.strideZ()};
    int64_t t_max[3], t_delta[3], step[3];
    int remaining = 0;
    for (int k = 0; k < 3; ++k) {
      const int n = end[k] - start[k];
      const double d = b[k] - a[k];  // nonzero when n != 0
      remaining += std::abs(n);
      if (n == 0) {
        t_max[k] = kNever;
        t_delta[k] = 0;
        step[k] = 0;
      } else {
        const double boundary = (n > 0 ? start[k] + 1 : start[k]) - a[k];  // same sign as d
        t_max[k] = static_cast<int64_t>(boundary / d * kOne + 0.5);
        t_delta[k] = static_cast<int64_t>(kOne / std::abs(d) + 0.5);
        step[k] = n > 0 ? strides[k] : -strides[k];
      }
    }
    // Every crossing an axis still needs lies before t = 1 (b) and every
    // further one after it, so the smallest t_max always belongs to an axis
    // that must still step: `remaining` steps end exactly in `end`. The axis
    // is picked with masks, not branches, so the loop does not stall on
    // mispredictions.
    int64_t tx = t_max[0], ty = t_max[1], tz = t_max[2];
    const int64_t dx = t_delta[0], dy = t_delta[1], dz = t_delta[2];
    const int64_t sx = step[0], sy = step[1], sz = step[2];
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

  static constexpr int64_t kOne = int64_t{1} << 40;
  static constexpr int64_t kNever = int64_t{1} << 60;

  const VoxelStateGrid& grid_;
  uint8_t mask_;
};

}  // namespace surface_nbv
