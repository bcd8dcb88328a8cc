#include "surface_nbv/map/tsdf_map.h"

#include <cmath>

namespace surface_nbv {

TsdfMap::TsdfMap(const TsdfConfig& config) : config_(config) {
  const Eigen::Vector3d cells = (config_.bounds.size() / config_.voxel_size).array().ceil();
  grid_voxels_ = cells.cast<int>();
  grid_blocks_ = (grid_voxels_.array() + kBlockSize - 1) / kBlockSize;
  slots_.assign(static_cast<size_t>(grid_blocks_.prod()), -1);
}

bool TsdfMap::voxelIndex(const Eigen::Vector3d& p_W, Eigen::Vector3i* voxel) const {
  const Eigen::Vector3d f = (p_W - config_.bounds.min) / config_.voxel_size;
  if (!f.allFinite() || (f.array() < 0.0).any() || (f.array() >= grid_voxels_.cast<double>().array()).any()) {
    return false;
  }
  *voxel = f.array().floor().cast<int>();
  return voxelInBounds(*voxel);
}

Eigen::Vector3d TsdfMap::voxelCenter(const Eigen::Vector3i& voxel) const {
  return config_.bounds.min + (voxel.cast<double>().array() + 0.5).matrix() * config_.voxel_size;
}

const TsdfBlock* TsdfMap::block(const Eigen::Vector3i& block_index) const {
  if (!blockInBounds(block_index)) return nullptr;
  const int32_t at = slots_[slot(block_index)];
  return at < 0 ? nullptr : blocks_[at].get();
}

TsdfBlock* TsdfMap::mutableBlock(const Eigen::Vector3i& block_index) {
  return const_cast<TsdfBlock*>(static_cast<const TsdfMap*>(this)->block(block_index));
}

TsdfBlock* TsdfMap::allocateBlock(const Eigen::Vector3i& block_index) {
  if (!blockInBounds(block_index)) return nullptr;
  int32_t& at = slots_[slot(block_index)];
  if (at >= 0) return blocks_[at].get();
  if (blocks_.size() >= config_.max_blocks) {
    ++refused_allocations_;
    return nullptr;
  }
  auto b = std::make_unique<TsdfBlock>();
  b->index = block_index;
  at = static_cast<int32_t>(blocks_.size());
  blocks_.push_back(std::move(b));
  return blocks_.back().get();
}

const TsdfVoxel* TsdfMap::voxel(const Eigen::Vector3i& voxel_index) const {
  if (!voxelInBounds(voxel_index)) return nullptr;
  const TsdfBlock* b = block(blockOfVoxel(voxel_index));
  if (b == nullptr) return nullptr;
  const Eigen::Vector3i l = localOfVoxel(voxel_index);
  return &b->at(l.x(), l.y(), l.z());
}

TsdfVoxel* TsdfMap::allocateVoxel(const Eigen::Vector3i& voxel_index) {
  if (!voxelInBounds(voxel_index)) return nullptr;
  TsdfBlock* b = allocateBlock(blockOfVoxel(voxel_index));
  if (b == nullptr) return nullptr;
  const Eigen::Vector3i l = localOfVoxel(voxel_index);
  return &b->at(l.x(), l.y(), l.z());
}

VoxelState TsdfMap::state(const Eigen::Vector3i& voxel_index) const {
  const TsdfVoxel* v = voxel(voxel_index);
  return v == nullptr ? VoxelState::kUnknown : stateOf(*v);
}

std::vector<Eigen::Vector3i> TsdfMap::blocksChangedSince(uint64_t since) const {
  std::vector<Eigen::Vector3i> out;
  for (const auto& b : blocks_) {
    if (b->change_stamp > since) out.push_back(b->index);
  }
  return out;
}

void TsdfMap::clear() {
  blocks_.clear();
  std::fill(slots_.begin(), slots_.end(), -1);
  ++change_counter_;
}

bool TsdfMap::adoptBlocks(TsdfMap* other) {
  if (other == this || other->grid_blocks_ != grid_blocks_) return false;
  blocks_.swap(other->blocks_);
  slots_.swap(other->slots_);
  other->clear();
  const uint64_t stamp = beginChange();
  for (const auto& b : blocks_) b->change_stamp = stamp;
  return true;
}

size_t TsdfMap::memoryBytes() const {
  return blocks_.size() * (sizeof(TsdfBlock) + sizeof(std::unique_ptr<TsdfBlock>)) + slots_.size() * sizeof(int32_t);
}

}  // namespace surface_nbv
