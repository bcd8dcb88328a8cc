// The TSDF map: voxels (phi, w) in blocks of 8^3, allocated on demand inside
// a fixed bounding box. Blocks are found through a dense table of block slots
// over the box (a perfect hash of the block index), so look-ups are O(1) and
// a point outside the box, or NaN, has no slot and is rejected; never turned
// into a giant index. Voxel (i, j, k) covers bounds.min + voxel_size * [i, i+1)
// (and so on), its centre at + 0.5 voxel. Every change stamps its block with a
// counter so several consumers (mesh, updates, collision map) each poll what
// changed since they last looked. Thread safety: concurrent reads are safe,
// writers must own disjoint blocks, and allocation is single-threaded.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/map/tsdf_config.h"

namespace surface_nbv {

struct TsdfVoxel {
  float phi = 0.0f;
  float w = 0.0f;
};

enum class VoxelState : uint8_t { kUnknown = 0, kOccupied = 1, kFree = 2 };

constexpr int kBlockSize = 8;  // voxels per block edge
constexpr int kBlockVoxels = kBlockSize * kBlockSize * kBlockSize;

struct TsdfBlock {
  Eigen::Vector3i index;           // block index: voxel index / kBlockSize
  uint64_t change_stamp = 0;       // map's counter value at the last change
  std::array<TsdfVoxel, kBlockVoxels> voxels;

  static int linear(int x, int y, int z) { return x + kBlockSize * (y + kBlockSize * z); }
  TsdfVoxel& at(int x, int y, int z) { return voxels[linear(x, y, z)]; }
  const TsdfVoxel& at(int x, int y, int z) const { return voxels[linear(x, y, z)]; }
};

class TsdfMap {
 public:
  // `config` must validate(); the constructor trusts it.
  explicit TsdfMap(const TsdfConfig& config);

  const TsdfConfig& config() const { return config_; }
  double voxelSize() const { return config_.voxel_size; }
  // Voxel grid size over the bounds, and block grid size.
  const Eigen::Vector3i& gridVoxels() const { return grid_voxels_; }
  const Eigen::Vector3i& gridBlocks() const { return grid_blocks_; }

  // Voxel containing p_W; false outside the bounds or for non-finite input.
  bool voxelIndex(const Eigen::Vector3d& p_W, Eigen::Vector3i* voxel) const;
  Eigen::Vector3d voxelCenter(const Eigen::Vector3i& voxel) const;
  bool voxelInBounds(const Eigen::Vector3i& voxel) const {
    return (voxel.array() >= 0).all() && (voxel.array() < grid_voxels_.array()).all();
  }
  bool blockInBounds(const Eigen::Vector3i& block) const {
    return (block.array() >= 0).all() && (block.array() < grid_blocks_.array()).all();
  }

  // nullptr when the block is not allocated or out of bounds.
  const TsdfBlock* block(const Eigen::Vector3i& block_index) const;
  TsdfBlock* mutableBlock(const Eigen::Vector3i& block_index);
  // Allocates on demand; nullptr out of bounds or at the block cap.
  TsdfBlock* allocateBlock(const Eigen::Vector3i& block_index);
  // The voxel, or nullptr if its block is not allocated (then it is unknown).
  const TsdfVoxel* voxel(const Eigen::Vector3i& voxel_index) const;
  TsdfVoxel* allocateVoxel(const Eigen::Vector3i& voxel_index);

  VoxelState state(const Eigen::Vector3i& voxel_index) const;
  VoxelState stateOf(const TsdfVoxel& v) const {
    if (v.w < config_.w_th) return VoxelState::kUnknown;
    return v.phi <= 0.0f ? VoxelState::kOccupied : VoxelState::kFree;
  }

  size_t numBlocks() const { return blocks_.size(); }
  // Allocated blocks in allocation order.
  const std::vector<std::unique_ptr<TsdfBlock>>& blocks() const { return blocks_; }
  // Requests refused because the cap was reached.
  uint64_t refusedAllocations() const { return refused_allocations_; }

  // Change tracking: stamp a block as changed now; list blocks changed after `since`.
  uint64_t changeCounter() const { return change_counter_; }
  uint64_t beginChange() { return ++change_counter_; }
  std::vector<Eigen::Vector3i> blocksChangedSince(uint64_t since) const;

  // Removes every block (the configuration stays).
  void clear();
  // Replaces this map's blocks by all of `other`'s (same grid required, else
  // false and nothing changes), leaving `other` empty. The adopted blocks get
  // one fresh stamp above every earlier one; config and counter carry on.
  bool adoptBlocks(TsdfMap* other);
  // Bytes held by blocks and the slot table.
  size_t memoryBytes() const;

  static Eigen::Vector3i blockOfVoxel(const Eigen::Vector3i& voxel) { return voxel / kBlockSize; }
  static Eigen::Vector3i localOfVoxel(const Eigen::Vector3i& voxel) {
    return voxel - blockOfVoxel(voxel) * kBlockSize;
  }

 private:
  size_t slot(const Eigen::Vector3i& block_index) const {
    return static_cast<size_t>(block_index.x()) +
           static_cast<size_t>(grid_blocks_.x()) *
               (static_cast<size_t>(block_index.y()) + static_cast<size_t>(grid_blocks_.y()) * block_index.z());
  }

  TsdfConfig config_;
  Eigen::Vector3i grid_voxels_, grid_blocks_;
  std::vector<int32_t> slots_;  // block slot -> position in blocks_, -1 if none
  std::vector<std::unique_ptr<TsdfBlock>> blocks_;
  uint64_t change_counter_ = 0;
  uint64_t refused_allocations_ = 0;
};

}  // namespace surface_nbv
