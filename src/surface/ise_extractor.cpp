#include "surface_nbv/surface/ise_extractor.h"

#include <algorithm>
#include <bitset>
#include <chrono>
#include <cstring>

#include "surface_nbv/surface/chunked_for.h"

namespace surface_nbv {
namespace {

static_assert(kBlockSize == 8, "the row masks assume 8-voxel block rows");

// Bit k of each of the 8 bytes of w, packed into one byte (byte i -> bit i).
inline uint32_t packBit(uint64_t w, int k) {
  return static_cast<uint32_t>((((w >> k) & 0x0101010101010101ULL) * 0x0102040810204080ULL) >> 56);
}

// Bit position of a one-bit state code.
constexpr int bitOf(uint8_t code) { return code == 1 ? 0 : (code == 2 ? 1 : 2); }
static_assert(VoxelStateGrid::kUnknown == 1 && VoxelStateGrid::kOccupied == 2 && VoxelStateGrid::kFree == 4,
              "one bit per state");

inline uint32_t dilateX(uint32_t m) { return m | (m << 1) | (m >> 1); }

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Eigen::Vector3i IseExtractor::blockOfSlot(size_t slot) const {
  const Eigen::Vector3i& g = states_.gridBlocks();
  const int x = static_cast<int>(slot % static_cast<size_t>(g.x()));
  const size_t yz = slot / static_cast<size_t>(g.x());
  return Eigen::Vector3i(x, static_cast<int>(yz % static_cast<size_t>(g.y())), static_cast<int>(yz / g.y()));
}

IseExtractor::BlockIses IseExtractor::examine(const Eigen::Vector3i& block) const {
  // Rows along x of the block and a one-voxel halo: 10-bit masks, bit 0 is
  // x = -1, bit 9 is x = 8 (block-local), indexed [z + 1][y + 1].
  constexpr int kU = bitOf(VoxelStateGrid::kUnknown), kO = bitOf(VoxelStateGrid::kOccupied),
                kF = bitOf(VoxelStateGrid::kFree);
  uint32_t unknown[10][10], occupied[10][10], free_bits[8][8];
  const Eigen::Vector3i base = block * kBlockSize;
  const uint8_t* data = states_.data();
  for (int z = 0; z < 10; ++z) {
    for (int y = 0; y < 10; ++y) {
      const uint8_t* row = data + states_.index(Eigen::Vector3i(base.x() - 1, base.y() + y - 1, base.z() + z - 1));
      uint64_t lo, hi;
      std::memcpy(&lo, row, 8);
      std::memcpy(&hi, row + 8, 8);
      unknown[z][y] = packBit(lo, kU) | ((packBit(hi, kU) & 3u) << 8);
      occupied[z][y] = packBit(lo, kO) | ((packBit(hi, kO) & 3u) << 8);
      if (z >= 1 && z <= 8 && y >= 1 && y <= 8) {
        free_bits[z - 1][y - 1] = ((packBit(lo, kF) >> 1) | ((packBit(hi, kF) & 1u) << 7)) & 0xFFu;
      }
    }
  }
  BlockIses out;
  int count = 0, scanned = 0;
  for (int z = 1; z <= 8; ++z) {
    uint64_t word = 0;
    for (int y = 1; y <= 8; ++y) {
      const uint32_t f = free_bits[z - 1][y - 1];
      if (f == 0) continue;
      const uint32_t u = unknown[z][y];
      const uint32_t touch_unknown =
          ((u << 1) | (u >> 1) | unknown[z][y - 1] | unknown[z][y + 1] | unknown[z - 1][y] | unknown[z + 1][y]) >> 1;
      const uint32_t touch_occupied =
          (dilateX(occupied[z][y]) | dilateX(occupied[z][y - 1]) | dilateX(occupied[z][y + 1]) |
           dilateX(occupied[z - 1][y]) | dilateX(occupied[z + 1][y]) | occupied[z - 1][y - 1] |
           occupied[z - 1][y + 1] | occupied[z + 1][y - 1] | occupied[z + 1][y + 1]) >> 1;
      const uint32_t ise = f & touch_unknown & touch_occupied & 0xFFu;
      const uint32_t done = f & ~touch_unknown & touch_occupied & 0xFFu;
      word |= static_cast<uint64_t>(ise) << (8 * (y - 1));
      count += static_cast<int>(std::bitset<8>(ise).count());
      scanned += static_cast<int>(std::bitset<8>(done).count());
    }
    out.bits[z - 1] = word;
  }
  out.count = static_cast<uint16_t>(count);
  out.scanned = static_cast<uint16_t>(scanned);
  return out;
}

IseUpdateStats IseExtractor::rebuild(const TsdfMap& map) {
  const auto t0 = std::chrono::steady_clock::now();
  states_.reset(map);
  const size_t slots = states_.numBlockSlots();
  blocks_.assign(slots, BlockIses());
  present_.assign(slots, 0);
  mark_.assign(slots, 0);
  mark_epoch_ = 0;
  total_ises_ = total_scanned_ = 0;
  std::vector<size_t> allocated;
  allocated.reserve(map.numBlocks());
  for (const auto& b : map.blocks()) allocated.push_back(states_.blockSlot(b->index));
  std::sort(allocated.begin(), allocated.end());
  IseUpdateStats stats;
  stats.full = true;
  apply(map, allocated, &stats);
  last_stamp_ = map.changeCounter();
  stats.ms = msSince(t0);
  return stats;
}

IseUpdateStats IseExtractor::update(const TsdfMap& map) {
  if (!states_.matches(map) || map.changeCounter() < last_stamp_) return rebuild(map);
  const auto t0 = std::chrono::steady_clock::now();
  if (++mark_epoch_ == 0) {
    std::fill(mark_.begin(), mark_.end(), 0);
    mark_epoch_ = 1;
  }
  std::vector<size_t> changed;
  for (const Eigen::Vector3i& b : map.blocksChangedSince(last_stamp_)) {
    const size_t slot = states_.blockSlot(b);
    mark_[slot] = mark_epoch_;
    changed.push_back(slot);
  }
  // Blocks can vanish (TsdfMap::clear, a mirror's snapshot): their voxels are unknown again.
  const int32_t allocated = static_cast<int32_t>(map.numBlocks());
  int32_t present_count = 0;
  for (size_t slot = 0; slot < present_.size(); ++slot) present_count += present_[slot];
  if (present_count > allocated || !changed.empty()) {
    for (size_t slot = 0; slot < present_.size(); ++slot) {
      if (present_[slot] && mark_[slot] != mark_epoch_ && map.block(blockOfSlot(slot)) == nullptr) {
        changed.push_back(slot);
      }
    }
  }
  std::sort(changed.begin(), changed.end());
  IseUpdateStats stats;
  apply(map, changed, &stats);
  last_stamp_ = map.changeCounter();
  stats.ms = msSince(t0);
  return stats;
}

void IseExtractor::apply(const TsdfMap& map, const std::vector<size_t>& changed, IseUpdateStats* stats) {
  stats->blocks_changed = changed.size();
  std::vector<uint8_t> state_changed(changed.size(), 0);
  parallelForChunked(changed.size(), threads_, 8, [&](size_t i) {
    state_changed[i] = states_.refreshBlock(map, blockOfSlot(changed[i])) ? 1 : 0;
  });
  changed_state_blocks_.clear();
  for (size_t i = 0; i < changed.size(); ++i)
    if (state_changed[i]) changed_state_blocks_.push_back(blockOfSlot(changed[i]));
  for (size_t slot : changed) present_[slot] = map.block(blockOfSlot(slot)) != nullptr ? 1 : 0;

  // The changed slots and their 26 neighbours, once each, by slot.
  if (++mark_epoch_ == 0) {
    std::fill(mark_.begin(), mark_.end(), 0);
    mark_epoch_ = 1;
  }
  std::vector<size_t> dirty;
  const Eigen::Vector3i& g = states_.gridBlocks();
  for (size_t slot : changed) {
    const Eigen::Vector3i b = blockOfSlot(slot);
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const Eigen::Vector3i n = b + Eigen::Vector3i(dx, dy, dz);
          if ((n.array() < 0).any() || (n.array() >= g.array()).any()) continue;
          const size_t s = states_.blockSlot(n);
          if (mark_[s] == mark_epoch_) continue;
          mark_[s] = mark_epoch_;
          dirty.push_back(s);
        }
      }
    }
  }
  std::sort(dirty.begin(), dirty.end());

  for (size_t slot : dirty) stats->blocks_examined += present_[slot];
  std::vector<BlockIses> fresh(dirty.size());
  parallelForChunked(dirty.size(), threads_, 8, [&](size_t i) {
    if (present_[dirty[i]]) fresh[i] = examine(blockOfSlot(dirty[i]));
  });
  changed_ise_blocks_.clear();
  for (size_t i = 0; i < dirty.size(); ++i) {
    BlockIses& old = blocks_[dirty[i]];
    size_t added = 0, removed = 0;
    for (int w = 0; w < kBlockSize; ++w) {
      added += std::bitset<64>(fresh[i].bits[w] & ~old.bits[w]).count();
      removed += std::bitset<64>(old.bits[w] & ~fresh[i].bits[w]).count();
    }
    if (added + removed > 0) changed_ise_blocks_.push_back(blockOfSlot(dirty[i]));
    stats->ises_added += added;
    stats->ises_removed += removed;
    total_ises_ = total_ises_ + fresh[i].count - old.count;
    total_scanned_ = total_scanned_ + fresh[i].scanned - old.scanned;
    old = fresh[i];
  }
}

bool IseExtractor::isIse(const Eigen::Vector3i& voxel) const {
  if (!states_.voxelInGrid(voxel)) return false;
  const BlockIses& b = blocks_[states_.blockSlot(TsdfMap::blockOfVoxel(voxel))];
  const Eigen::Vector3i l = TsdfMap::localOfVoxel(voxel);
  return (b.bits[l.z()] >> (l.x() + kBlockSize * l.y())) & 1u;
}

std::vector<Eigen::Vector3i> IseExtractor::ises() const {
  std::vector<Eigen::Vector3i> out;
  out.reserve(total_ises_);
  for (size_t slot = 0; slot < blocks_.size(); ++slot) {
    const BlockIses& b = blocks_[slot];
    if (b.count == 0) continue;
    const Eigen::Vector3i base = blockOfSlot(slot) * kBlockSize;
    for (int z = 0; z < kBlockSize; ++z) {
      for (uint64_t w = b.bits[z]; w != 0; w &= w - 1) {
        const int bit = __builtin_ctzll(w);
        out.emplace_back(base.x() + bit % kBlockSize, base.y() + bit / kBlockSize, base.z() + z);
      }
    }
  }
  return out;
}

}  // namespace surface_nbv
