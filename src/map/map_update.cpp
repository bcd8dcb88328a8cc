#include "surface_nbv/map/map_update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace surface_nbv {

namespace {

std::string describe(const Eigen::Vector3i& index) {
  std::ostringstream s;
  s << "(" << index.x() << ", " << index.y() << ", " << index.z() << ")";
  return s.str();
}

std::string describe(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

// Bit equality, so that -0.0 and 0.0 differ and the mirror stays bit-identical.
bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

bool sameVoxels(const TsdfBlock& block, const BlockData& data) {
  for (int i = 0; i < kBlockVoxels; ++i) {
    if (!sameBits(block.voxels[i].phi, data.phi[i]) || !sameBits(block.voxels[i].w, data.w[i])) return false;
  }
  return true;
}

}  // namespace

Status makeUpdate(const TsdfMap& map, uint64_t since_stamp, uint64_t sequence, bool snapshot, MapUpdate* update) {
  if (update == nullptr) return Status::Error("makeUpdate: no output update");
  update->sequence = sequence;
  update->snapshot = snapshot;
  update->voxel_size = map.voxelSize();
  update->w_th = map.config().w_th;
  update->bounds = map.config().bounds;
  update->blocks.clear();
  for (const auto& block : map.blocks()) {
    if (!snapshot && block->change_stamp <= since_stamp) continue;
    BlockData data;
    data.index = block->index;
    data.phi.resize(kBlockVoxels);
    data.w.resize(kBlockVoxels);
    for (int i = 0; i < kBlockVoxels; ++i) {
      data.phi[i] = block->voxels[i].phi;
      data.w[i] = block->voxels[i].w;
    }
    update->blocks.push_back(std::move(data));
  }
  return Status::Ok();
}

const char* toString(ApplyResult result) {
  switch (result) {
    case ApplyResult::kApplied: return "applied";
    case ApplyResult::kIgnored: return "ignored";
    case ApplyResult::kNeedSnapshot: return "need_snapshot";
    case ApplyResult::kIncompatible: return "incompatible";
    case ApplyResult::kMalformed: return "malformed";
  }
  return "unknown";
}

MapMirror::MapMirror(const TsdfConfig& config) : map_(config) {}

ApplyResult MapMirror::apply(const MapUpdate& update) {
  ApplyResult header_result = ApplyResult::kMalformed;
  const Status header = checkHeader(update, &header_result);
  if (!header) return refuse(header_result, header.message());
  const Status blocks = checkBlocks(update);
  if (!blocks) return refuse(ApplyResult::kMalformed, blocks.message());

  const std::string seq = std::to_string(update.sequence);
  if (!update.snapshot) {
    if (!synced_) return refuse(ApplyResult::kNeedSnapshot, "update " + seq + " arrived before any snapshot");
    if (update.sequence <= last_sequence_) {
      if (++stale_run_ > kStaleRunLimit) {
        return refuse(ApplyResult::kNeedSnapshot, std::to_string(stale_run_) + " stale updates in a row (now " +
                                                      seq + "): the publisher restarted its count?");
      }
      return refuse(ApplyResult::kIgnored,
                    "update " + seq + " is not newer than the last applied " + std::to_string(last_sequence_));
    }
    if (update.sequence != last_sequence_ + 1) {
      return refuse(ApplyResult::kNeedSnapshot,
                    "gap: expected update " + std::to_string(last_sequence_ + 1) + ", got " + seq);
    }
  }

  size_t blocks_after = update.blocks.size();
  if (!update.snapshot) {
    blocks_after = map_.numBlocks();
    for (const BlockData& b : update.blocks) blocks_after += map_.block(b.index) == nullptr ? 1 : 0;
  }
  if (blocks_after > map_.config().max_blocks) {
    return refuse(ApplyResult::kIncompatible, "update " + seq + " needs " + std::to_string(blocks_after) +
                                                  " blocks, the mirror's max_blocks is " +
                                                  std::to_string(map_.config().max_blocks));
  }

  applyBlocks(update);
  synced_ = true;
  last_sequence_ = update.sequence;
  stale_run_ = 0;
  ++counters_.applied;
  if (update.snapshot) ++counters_.snapshots;
  last_error_.clear();
  return ApplyResult::kApplied;
}

Status MapMirror::checkHeader(const MapUpdate& update, ApplyResult* result) const {
  *result = ApplyResult::kMalformed;
  if (!std::isfinite(update.voxel_size) || update.voxel_size <= 0.0) {
    return Status::Error("voxel_size " + std::to_string(update.voxel_size) + " is not > 0");
  }
  if (!std::isfinite(update.w_th)) return Status::Error("w_th is not finite");
  if (!update.bounds.min.allFinite() || !update.bounds.max.allFinite()) return Status::Error("bounds are not finite");

  *result = ApplyResult::kIncompatible;
  const TsdfConfig& mine = map_.config();
  if (update.voxel_size != mine.voxel_size) {
    return Status::Error("voxel_size " + std::to_string(update.voxel_size) + " differs from the mirror's " +
                         std::to_string(mine.voxel_size));
  }
  if (update.bounds.min != mine.bounds.min || update.bounds.max != mine.bounds.max) {
    return Status::Error("bounds " + describe(update.bounds.min) + " - " + describe(update.bounds.max) +
                         " differ from the mirror's " + describe(mine.bounds.min) + " - " + describe(mine.bounds.max));
  }
  if (!sameBits(update.w_th, mine.w_th)) {
    return Status::Error("w_th " + std::to_string(update.w_th) + " differs from the mirror's " +
                         std::to_string(mine.w_th));
  }
  return Status::Ok();
}

Status MapMirror::checkBlocks(const MapUpdate& update) const {
  std::vector<int64_t> slots;
  slots.reserve(update.blocks.size());
  const Eigen::Vector3i& grid = map_.gridBlocks();
  for (size_t k = 0; k < update.blocks.size(); ++k) {
    const BlockData& b = update.blocks[k];
    const std::string name = "block " + std::to_string(k) + " " + describe(b.index);
    if (!map_.blockInBounds(b.index)) {
      return Status::Error(name + " is outside the block grid " + describe(grid));
    }
    if (b.phi.size() != static_cast<size_t>(kBlockVoxels) || b.w.size() != static_cast<size_t>(kBlockVoxels)) {
      return Status::Error(name + " holds " + std::to_string(b.phi.size()) + " phi and " + std::to_string(b.w.size()) +
                           " w values, expected " + std::to_string(kBlockVoxels) + " each");
    }
    for (int i = 0; i < kBlockVoxels; ++i) {
      if (!std::isfinite(b.phi[i]) || !std::isfinite(b.w[i]) || b.w[i] < 0.0f) {
        return Status::Error(name + " voxel " + std::to_string(i) + " has phi " + std::to_string(b.phi[i]) +
                             ", w " + std::to_string(b.w[i]) + " (expected finite, w >= 0)");
      }
    }
    slots.push_back(b.index.x() + static_cast<int64_t>(grid.x()) * (b.index.y() + static_cast<int64_t>(grid.y()) *
                                                                                        b.index.z()));
  }
  std::sort(slots.begin(), slots.end());
  if (std::adjacent_find(slots.begin(), slots.end()) != slots.end()) {
    return Status::Error("a block appears twice in the update");
  }
  return Status::Ok();
}

ApplyResult MapMirror::refuse(ApplyResult result, const std::string& why) {
  switch (result) {
    case ApplyResult::kIgnored: ++counters_.ignored; break;
    case ApplyResult::kNeedSnapshot: ++counters_.gaps; break;
    case ApplyResult::kIncompatible: ++counters_.incompatible; break;
    case ApplyResult::kMalformed: ++counters_.malformed; break;
    case ApplyResult::kApplied: break;
  }
  last_error_ = why;
  return result;
}

void MapMirror::applyBlocks(const MapUpdate& update) {
  if (update.snapshot) {
    size_t kept = 0;
    for (const BlockData& b : update.blocks) kept += map_.block(b.index) != nullptr ? 1 : 0;
    if (kept < map_.numBlocks()) {
      map_.clear();
      ++resets_;
    }
  }
  const uint64_t stamp = map_.beginChange();
  for (const BlockData& data : update.blocks) {
    TsdfBlock* block = map_.mutableBlock(data.index);
    const bool fresh = block == nullptr;
    if (fresh) block = map_.allocateBlock(data.index);  // cannot fail: bounds and cap were checked
    if (!fresh && sameVoxels(*block, data)) continue;
    for (int i = 0; i < kBlockVoxels; ++i) {
      block->voxels[i].phi = data.phi[i];
      block->voxels[i].w = data.w[i];
    }
    block->change_stamp = stamp;
  }
}

}  // namespace surface_nbv
