#include "surface_nbv/surface/voxel_state_grid.h"

#include <algorithm>
#include <cstring>

namespace surface_nbv {

void VoxelStateGrid::reset(const TsdfMap& map) {
  grid_voxels_ = map.gridVoxels();
  grid_blocks_ = map.gridBlocks();
  voxel_size_ = map.voxelSize();
  w_th_ = map.config().w_th;
  origin_ = map.config().bounds.min;
  const Eigen::Vector3i padded = grid_blocks_ * kBlockSize + Eigen::Vector3i::Constant(2);
  stride_y_ = padded.x();
  stride_z_ = static_cast<int64_t>(padded.x()) * padded.y();
  // 16 spare bytes so that 8-byte row loads near the end stay inside.
  data_.assign(static_cast<size_t>(stride_z_) * padded.z() + 16, kOutside);
  for (int z = 0; z < grid_voxels_.z(); ++z) {
    for (int y = 0; y < grid_voxels_.y(); ++y) {
      uint8_t* row = &data_[index(Eigen::Vector3i(0, y, z))];
      std::fill(row, row + grid_voxels_.x(), kUnknown);
    }
  }
}

bool VoxelStateGrid::matches(const TsdfMap& map) const {
  return !data_.empty() && grid_voxels_ == map.gridVoxels() && voxel_size_ == map.voxelSize() &&
         w_th_ == map.config().w_th && origin_ == map.config().bounds.min;
}

bool VoxelStateGrid::refreshBlock(const TsdfMap& map, const Eigen::Vector3i& block) {
  const TsdfBlock* b = map.block(block);
  const Eigen::Vector3i base = block * kBlockSize;
  const float w_th = w_th_;
  uint8_t differ = 0;
  for (int z = 0; z < kBlockSize; ++z) {
    for (int y = 0; y < kBlockSize; ++y) {
      const Eigen::Vector3i first(base.x(), base.y() + y, base.z() + z);
      uint8_t* row = &data_[index(first)];
      const bool row_in = first.y() < grid_voxels_.y() && first.z() < grid_voxels_.z();
      for (int x = 0; x < kBlockSize; ++x) {
        uint8_t s = kOutside;
        if (row_in && base.x() + x < grid_voxels_.x()) {
          if (b == nullptr) {
            s = kUnknown;
          } else {
            const TsdfVoxel& v = b->at(x, y, z);
            s = v.w < w_th ? kUnknown : (v.phi <= 0.0f ? kOccupied : kFree);
          }
        }
        differ |= row[x] ^ s;
        row[x] = s;
      }
    }
  }
  return differ != 0;
}

}  // namespace surface_nbv
