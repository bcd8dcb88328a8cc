// The sets C_q of eq. 3: for each viewpoint, the ISEs whose voxel centres
// its camera sees. A centre is seen when it lies inside the frustum of the
// level camera at the viewpoint (pinhole FOV, depth on the optical axis
// within [min_range, max_range], as DepthCamera::sees) and the 3D DDA from
// the camera to it is not blocked (VoxelRayCaster: occupied voxels, and
// unknown ones when unknown_blocks_visibility). Candidates come from the
// blocks whose bounding spheres meet the frustum. Runs on `threads` threads
// one viewpoint at a time; the result does not depend on the count.
#pragma once

#include <cstdint>
#include <vector>

#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/surface/surface_config.h"
#include "surface_nbv/surface/voxel_ray_caster.h"

namespace surface_nbv {

class VisibilityEvaluator {
 public:
  // `config` must validate(); the constructor trusts it.
  explicit VisibilityEvaluator(const SurfaceConfig& config);

  // Fills viewpoints[i].visible with ascending indices into `ises`; returns
  // the voxel steps walked by all rays. With `todo`, only the viewpoints i
  // with (*todo)[i] set; with `steps`, steps[i] gets viewpoint i's (0 for
  // those not evaluated).
  uint64_t evaluate(const VoxelRayCaster& rays, const std::vector<Ise>& ises, std::vector<Viewpoint>* viewpoints,
                    const std::vector<uint8_t>* todo = nullptr, std::vector<uint64_t>* steps = nullptr) const;

  // Whether the camera at `viewpoint` has p_W inside its frustum.
  bool inFrustum(const Viewpoint& viewpoint, const Eigen::Vector3d& p_W) const;

 private:
  // ISEs grouped by block slot: ises_of_slot[begin[s] .. begin[s + 1]).
  struct BlockIndex {
    std::vector<uint32_t> begin;
    std::vector<uint32_t> order;
  };
  BlockIndex index(const VoxelStateGrid& grid, const std::vector<Ise>& ises) const;
  void visibleFrom(const VoxelRayCaster& rays, const BlockIndex& index, const std::vector<Ise>& ises,
                   const Viewpoint& viewpoint, std::vector<uint32_t>* visible, uint64_t* steps) const;

  SurfaceConfig config_;
  double tan_half_h_, tan_half_v_, sin_half_h_, cos_half_h_, sin_half_v_, cos_half_v_;
  double pitch_;  // rad, the mount's pitch down
};

}  // namespace surface_nbv
