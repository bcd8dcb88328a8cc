#include "surface_nbv/map/tsdf_config.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {

const char* toString(InvalidPixelPolicy policy) {
  switch (policy) {
    case InvalidPixelPolicy::kIgnore: return "ignore";
    case InvalidPixelPolicy::kClearToMaxRange: return "clear";
    case InvalidPixelPolicy::kClearInfinite: return "clear_inf";
  }
  return "unknown";
}

bool parseInvalidPixelPolicy(const std::string& text, InvalidPixelPolicy* policy) {
  if (text == "ignore") *policy = InvalidPixelPolicy::kIgnore;
  else if (text == "clear") *policy = InvalidPixelPolicy::kClearToMaxRange;
  else if (text == "clear_inf") *policy = InvalidPixelPolicy::kClearInfinite;
  else return false;
  return true;
}

TsdfConfig TsdfConfig::meshLayerConfig() const {
  TsdfConfig c = *this;
  c.voxel_size = meshVoxelSize();
  c.mesh_voxel_size = 0.0;
  c.truncation = mesh_truncation;
  c.mesh_truncation = 0.0;
  c.weight_dropoff = mesh_weight_dropoff;
  c.mesh_weight_dropoff = false;
  c.band_allocation = true;
  return c;
}

Status TsdfConfig::validate() const {
  if (!std::isfinite(voxel_size) || voxel_size <= 0.0) return Status::Error("voxel_size expected > 0");
  if (!std::isfinite(truncation) || truncation < 0.0) return Status::Error("truncation expected >= 0 (0 = 3 voxels)");
  if (truncation > 0.0 && truncation < voxel_size) return Status::Error("truncation expected >= voxel_size");
  if (!std::isfinite(mesh_voxel_size) || mesh_voxel_size < 0.0) {
    return Status::Error("mesh_voxel_size expected >= 0 (0 = voxel_size)");
  }
  if (!std::isfinite(mesh_truncation) || mesh_truncation < 0.0 ||
      (mesh_truncation > 0.0 && mesh_truncation < meshVoxelSize())) {
    return Status::Error("mesh_truncation expected 0 (mesh the map itself) or >= the mesh layer's voxel size");
  }
  if (mesh_voxel_size > 0.0 && mesh_truncation <= 0.0) {
    return Status::Error("mesh_voxel_size needs a mesh layer (mesh_truncation > 0)");
  }
  if (mesh_weight_dropoff && mesh_truncation <= 0.0) {
    return Status::Error("mesh_weight_dropoff needs a mesh layer (mesh_truncation > 0)");
  }
  if (!std::isfinite(w_th) || w_th <= 0.0f) return Status::Error("w_th expected > 0");
  if (!std::isfinite(mesh_min_weight)) return Status::Error("mesh_min_weight expected finite (< 0 selects w_th)");
  if (!std::isfinite(max_weight) || max_weight < 0.0f || (max_weight > 0.0f && max_weight < w_th)) {
    return Status::Error("max_weight expected 0 (no cap) or >= w_th");
  }
  if (!bounds.min.allFinite() || !bounds.max.allFinite() || (bounds.max.array() <= bounds.min.array()).any()) {
    return Status::Error("bounds expected finite with bounds_min < bounds_max on every axis");
  }
  const Eigen::Array3d blocks = (bounds.size() / (std::min(voxel_size, meshVoxelSize()) * 8)).array().ceil();
  if (blocks.prod() > 64e6) {
    return Status::Error("bounds hold " + std::to_string(static_cast<long long>(blocks.prod())) +
                         " block slots at this voxel_size (limit 64M): shrink the bounds or grow voxel_size");
  }
  if (max_blocks == 0) return Status::Error("max_blocks expected > 0");
  if (threads < 1 || threads > 64) return Status::Error("threads expected in [1, 64]");
  return Status::Ok();
}

}  // namespace surface_nbv
