// The set C of incomplete surface elements (docs/method.md eq. 1) of a TsdfMap,
// kept incrementally: an update re-reads only the blocks stamped since the
// last one (or that vanished) and re-examines them and their 26 neighbour
// blocks. A voxel is an ISE iff it is known empty, has an unknown 6-neighbour
// and a known occupied 18-neighbour; voxels outside the map's voxel grid are
// neither unknown nor occupied (they can never be scanned). Also counts the
// scanned elements (Def. 3) among surface voxels: known empty voxels with a
// known occupied 18-neighbour and no unknown 6-neighbour. Single-threaded
// use; update() runs on `threads` threads and gives the same answer for any
// count. ISE ids are linear voxel indices (VoxelStateGrid::voxelId).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/surface/voxel_state_grid.h"

namespace surface_nbv {

struct IseUpdateStats {
  bool full = false;            // everything was re-extracted
  size_t blocks_changed = 0;    // block slots re-read from the map
  size_t blocks_examined = 0;   // allocated blocks whose ISEs were recomputed
  size_t ises_added = 0, ises_removed = 0;
  double ms = 0.0;
};

class IseExtractor {
 public:
  explicit IseExtractor(int threads = 1) : threads_(threads < 1 ? 1 : threads) {}

  // Brings C up to date with `map`. The first call, a map of another
  // geometry (grid, voxel size, bounds, W_th) or a change counter that went
  // back re-extracts everything.
  IseUpdateStats update(const TsdfMap& map);
  // Re-reads every block and re-extracts everything.
  IseUpdateStats rebuild(const TsdfMap& map);

  size_t size() const { return total_ises_; }          // |C|
  size_t scannedCount() const { return total_scanned_; }
  bool isIse(const Eigen::Vector3i& voxel) const;
  // Every ISE voxel, by block slot, then by TsdfBlock::linear within a block.
  std::vector<Eigen::Vector3i> ises() const;
  // Blocks whose ISEs changed in the last update, by slot.
  const std::vector<Eigen::Vector3i>& changedIseBlocks() const { return changed_ise_blocks_; }
  // Blocks in which some voxel's state (states()) changed in the last update
  // or rebuild, by slot: nothing else of states() changed.
  const std::vector<Eigen::Vector3i>& changedStateBlocks() const { return changed_state_blocks_; }
  // The voxel states as of the last update, for eq. 2 and ray casting.
  const VoxelStateGrid& states() const { return states_; }
  int threads() const { return threads_; }

 private:
  struct BlockIses {
    std::array<uint64_t, kBlockSize> bits{};  // word z, bit x + 8 y
    uint16_t count = 0;
    uint16_t scanned = 0;
  };
  // Recomputes the ISEs of one block slot from states_.
  BlockIses examine(const Eigen::Vector3i& block) const;
  Eigen::Vector3i blockOfSlot(size_t slot) const;
  // Re-reads `changed` slots, re-examines them and their neighbours.
  void apply(const TsdfMap& map, const std::vector<size_t>& changed, IseUpdateStats* stats);

  int threads_;
  VoxelStateGrid states_;
  std::vector<BlockIses> blocks_;   // per block slot
  std::vector<uint8_t> present_;    // per block slot: allocated in the map at the last update
  std::vector<uint32_t> mark_;      // per block slot: scratch for de-duplication
  uint32_t mark_epoch_ = 0;
  uint64_t last_stamp_ = 0;
  size_t total_ises_ = 0, total_scanned_ = 0;
  std::vector<Eigen::Vector3i> changed_ise_blocks_;
  std::vector<Eigen::Vector3i> changed_state_blocks_;
};

}  // namespace surface_nbv
