// A dense copy of a TsdfMap's voxel states, one byte per voxel, for the
// neighbourhood tests of eq. 1 and 2 and for ray casting. The array covers
// every voxel of every block slot plus one voxel on each side; voxels outside
// the map's voxel grid read kOutside (neither unknown, occupied nor free), so
// neighbour reads and ray walks between in-grid voxels need no bounds check.
// Thread safety: refreshBlock() on distinct blocks may run concurrently,
// reads are safe while no refresh runs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/map/tsdf_map.h"

namespace surface_nbv {

class VoxelStateGrid {
 public:
  static constexpr uint8_t kOutside = 0;
  static constexpr uint8_t kUnknown = 1;
  static constexpr uint8_t kOccupied = 2;
  static constexpr uint8_t kFree = 4;

  // Sizes the grid for `map` (its voxel grid, voxel size and bounds) with
  // every in-grid voxel unknown. Blocks must then be refreshed.
  void reset(const TsdfMap& map);
  // True when reset() was called for a map with this geometry.
  bool matches(const TsdfMap& map) const;
  // Copies the states of one block slot from `map` (unknown if unallocated),
  // and says whether a voxel's state differs from the one held before.
  bool refreshBlock(const TsdfMap& map, const Eigen::Vector3i& block);

  // Voxel (i, j, k) with each coordinate in [-1, 8 * blocks]; see the contract above.
  size_t index(const Eigen::Vector3i& voxel) const {
    return static_cast<size_t>(voxel.x() + 1) +
           static_cast<size_t>(stride_y_) * static_cast<size_t>(voxel.y() + 1) +
           static_cast<size_t>(stride_z_) * static_cast<size_t>(voxel.z() + 1);
  }
  uint8_t at(const Eigen::Vector3i& voxel) const { return data_[index(voxel)]; }
  const uint8_t* data() const { return data_.data(); }
  int64_t strideY() const { return stride_y_; }
  int64_t strideZ() const { return stride_z_; }

  const Eigen::Vector3i& gridVoxels() const { return grid_voxels_; }
  const Eigen::Vector3i& gridBlocks() const { return grid_blocks_; }
  bool voxelInGrid(const Eigen::Vector3i& v) const {
    return (v.array() >= 0).all() && (v.array() < grid_voxels_.array()).all();
  }
  // The voxel containing p_W; false outside the voxel grid or for non-finite input.
  bool voxelOf(const Eigen::Vector3d& p_W, Eigen::Vector3i* voxel) const {
    const Eigen::Vector3d f = ((p_W - origin_) / voxel_size_).array().floor();
    if (!f.allFinite() || (f.array() < 0.0).any() || (f.array() >= grid_voxels_.cast<double>().array()).any()) {
      return false;
    }
    *voxel = f.cast<int>();
    return true;
  }
  double voxelSize() const { return voxel_size_; }
  const Eigen::Vector3d& origin() const { return origin_; }  // bounds min, world frame
  Eigen::Vector3d voxelCenter(const Eigen::Vector3i& v) const {
    return origin_ + (v.cast<double>().array() + 0.5).matrix() * voxel_size_;
  }
  // Linear voxel index over the map's voxel grid (x fastest): a stable ISE id.
  uint64_t voxelId(const Eigen::Vector3i& v) const {
    return static_cast<uint64_t>(v.x()) +
           static_cast<uint64_t>(grid_voxels_.x()) *
               (static_cast<uint64_t>(v.y()) + static_cast<uint64_t>(grid_voxels_.y()) * static_cast<uint64_t>(v.z()));
  }
  // Block slot over the block grid (x fastest).
  size_t blockSlot(const Eigen::Vector3i& b) const {
    return static_cast<size_t>(b.x()) +
           static_cast<size_t>(grid_blocks_.x()) *
               (static_cast<size_t>(b.y()) + static_cast<size_t>(grid_blocks_.y()) * static_cast<size_t>(b.z()));
  }
  size_t numBlockSlots() const { return static_cast<size_t>(grid_blocks_.prod()); }

 private:
  std::vector<uint8_t> data_;
  Eigen::Vector3i grid_voxels_{0, 0, 0}, grid_blocks_{0, 0, 0};
  int64_t stride_y_ = 0, stride_z_ = 0;
  double voxel_size_ = 0.0;
  float w_th_ = 0.0f;
  Eigen::Vector3d origin_{0, 0, 0};
};

}  // namespace surface_nbv
