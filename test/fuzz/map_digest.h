// Digests of a TsdfMap and of a MapMirror for the fuzz tests: a 64-bit FNV-1a
// hash over everything a consumer can observe (blocks in allocation order
// with their index, change stamp and voxel bits, the change counter, and the
// mirror's sync state), so "a refused update changed nothing" is one equality.
// The mirror's refusal counters and last error are left out on purpose: a
// refusal is expected to count itself. Also a check of the map invariants
// that every accepted update must keep.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "surface_nbv/map/map_update.h"
#include "surface_nbv/map/tsdf_map.h"

namespace surface_nbv {
namespace fuzz {

class Digest {
 public:
  void bytes(const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    for (size_t i = 0; i < size; ++i) {
      hash_ ^= p[i];
      hash_ *= 1099511628211ull;
    }
  }
  template <typename T>
  void value(const T& v) {
    bytes(&v, sizeof(v));
  }
  uint64_t hash() const { return hash_; }

 private:
  uint64_t hash_ = 1469598103934665603ull;
};

inline uint64_t mapDigest(const TsdfMap& map) {
  Digest d;
  d.value(map.numBlocks());
  d.value(map.changeCounter());
  for (const auto& block : map.blocks()) {
    d.value(block->index.x());
    d.value(block->index.y());
    d.value(block->index.z());
    d.value(block->change_stamp);
    d.bytes(block->voxels.data(), sizeof(block->voxels));
  }
  return d.hash();
}

inline uint64_t mirrorDigest(const MapMirror& mirror) {
  Digest d;
  d.value(mapDigest(mirror.map()));
  d.value(mirror.synced());
  d.value(mirror.lastSequence());
  d.value(mirror.resets());
  return d.hash();
}

// "" when the map is sound: at most max_blocks blocks, each in bounds, found
// again by its own index, with finite phi and finite w >= 0. Else the first
// fault found.
inline std::string mapFault(const TsdfMap& map) {
  if (map.numBlocks() > map.config().max_blocks) return "more blocks than max_blocks";
  for (const auto& block : map.blocks()) {
    if (!map.blockInBounds(block->index)) return "a block lies outside the block grid";
    if (map.block(block->index) != block.get()) return "a block is not found by its own index";
    if (block->change_stamp > map.changeCounter()) return "a change stamp is ahead of the counter";
    for (const TsdfVoxel& v : block->voxels) {
      if (!std::isfinite(v.phi) || !std::isfinite(v.w) || v.w < 0.0f) return "a voxel is non-finite or has w < 0";
    }
  }
  return "";
}

// True when every block of `update` is in `map` with exactly its voxel bits.
inline bool mapHoldsUpdate(const TsdfMap& map, const MapUpdate& update) {
  for (const BlockData& data : update.blocks) {
    const TsdfBlock* block = map.block(data.index);
    if (block == nullptr || data.phi.size() != static_cast<size_t>(kBlockVoxels) ||
        data.w.size() != static_cast<size_t>(kBlockVoxels)) {
      return false;
    }
    for (int i = 0; i < kBlockVoxels; ++i) {
      if (std::memcmp(&block->voxels[i].phi, &data.phi[i], sizeof(float)) != 0 ||
          std::memcmp(&block->voxels[i].w, &data.w[i], sizeof(float)) != 0) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace fuzz
}  // namespace surface_nbv
