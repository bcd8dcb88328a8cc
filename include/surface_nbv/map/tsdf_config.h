// Parameters of the TSDF map (docs/method.md, "TSDF map"). Lengths in metres.
#pragma once

#include <cstddef>
#include <string>

#include "surface_nbv/common.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// What an invalid pixel (NaN, zero, outside the depth range) does.
enum class InvalidPixelPolicy {
  kIgnore,            // nothing: the ray carries no information
  kClearToMaxRange,   // free space along the ray up to max range (no surface)
  // REP 117: +Inf ("no return within max range") and depths beyond max range
  // clear free space up to max range, every other invalid pixel (NaN, -Inf =
  // too close, zero, below min range) is ignored. Safe next to close objects,
  // and open sky becomes known free space.
  kClearInfinite,
};

const char* toString(InvalidPixelPolicy policy);
bool parseInvalidPixelPolicy(const std::string& text, InvalidPixelPolicy* policy);

struct TsdfConfig {
  double voxel_size = 0.3;        // rho_v
  double truncation = 0.0;        // 0 selects 3 voxels
  // Truncation of the mesh layer, a second TSDF fused from the same frames
  // that the reconstruction mesh comes from (mesh_layer.h); 0 meshes this map.
  double mesh_truncation = 0.0;
  // Voxel size of the mesh layer; 0 keeps voxel_size. A finer layer puts
  // Marching Cubes' zero crossings closer to convex edges, where a projective
  // TSDF pulls them into the object by up to a voxel.
  double mesh_voxel_size = 0.0;
  // Weight drop-off behind surfaces: an update with sdf < -voxel_size counts
  // (t + sdf) / (t - voxel_size) of its weight, down to nothing at -t (t the
  // truncation). Behind a thin part (a parapet, a wall's top, a pipe) the
  // voxels lie in free space on the far side, and full-weight negative
  // updates from the near side outvote the fewer views that see that side,
  // filling concave corners there. mesh_weight_dropoff sets it for the mesh
  // layer: on the power plant's 780 m flights it adds coverage without
  // changing the flights (docs/planner_experiments.md, session 10).
  bool weight_dropoff = false;
  bool mesh_weight_dropoff = false;
  // New blocks only within the truncation of a measured depth: a block that
  // lies wholly in front of every surface in view by more than the
  // truncation is not allocated (blocks that exist are updated as before).
  // Free space far from surfaces stays unknown, so it is for maps that are
  // only meshed: the mesh layer sets it (meshLayerConfig()).
  bool band_allocation = false;
  float w_th = 0.3f;              // W_th: known iff w >= w_th
  float max_weight = 0.0f;        // cap on w; 0 = no cap
  // Weight a voxel needs to be meshed (Marching Cubes corners): < 0 uses w_th
  // (known voxels only); >= 0 meshes every voxel whose weight exceeds it, as
  // the fusion of Zeng et al. (2017) the paper used does (w > 0).
  float mesh_min_weight = -1.0f;
  AlignedBox bounds{Eigen::Vector3d(-10, -10, -1), Eigen::Vector3d(10, 10, 9)};
  size_t max_blocks = 1u << 20;   // allocation stops there (counted, never a crash)
  InvalidPixelPolicy invalid_pixels = InvalidPixelPolicy::kClearInfinite;
  int threads = 1;                // integration threads

  double truncationDistance() const { return truncation > 0.0 ? truncation : 3.0 * voxel_size; }
  double meshVoxelSize() const { return mesh_voxel_size > 0.0 ? mesh_voxel_size : voxel_size; }
  // Whether mesh_truncation asks for a mesh layer of its own.
  bool hasMeshLayer() const {
    return mesh_truncation > 0.0 && (mesh_truncation != truncationDistance() ||
                                     mesh_weight_dropoff != weight_dropoff || meshVoxelSize() != voxel_size);
  }
  // This config with voxel_size = meshVoxelSize(), truncation =
  // mesh_truncation, weight_dropoff = mesh_weight_dropoff, band_allocation
  // and no mesh layer of its own.
  TsdfConfig meshLayerConfig() const;
  // Names the first bad key, e.g. "voxel_size expected > 0".
  Status validate() const;
};

}  // namespace surface_nbv
