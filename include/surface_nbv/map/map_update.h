// Map updates: how the TSDF map travels from the mapper to the nodes that
// mirror it (DESIGN.md, `tsdf/update`). An update carries whole 8^3 blocks,
// either every allocated block (a snapshot) or those changed since a stamp
// (incremental), numbered by a publisher sequence so that a receiver can tell
// a missed update from the next one. Voxel arrays follow TsdfBlock::linear
// (x fastest), kBlockVoxels entries each.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/common.h"
#include "surface_nbv/map/tsdf_config.h"
#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// One block of an update: its block index and kBlockVoxels values of phi and w.
struct BlockData {
  Eigen::Vector3i index = Eigen::Vector3i::Zero();
  std::vector<float> phi, w;
};

struct MapUpdate {
  uint64_t sequence = 0;   // publisher's count; an incremental update follows sequence - 1
  bool snapshot = false;   // true: `blocks` is the whole map, replacing what the receiver has
  double voxel_size = 0.0;
  float w_th = 0.0f;
  AlignedBox bounds;
  std::vector<BlockData> blocks;
};

// Fills `update` from `map`: every allocated block when `snapshot`, else the
// blocks whose change stamp is greater than `since_stamp`, in allocation
// order. The publisher reads map.changeCounter() when it makes an update and
// passes that value as `since_stamp` of the next one. Incremental updates
// cannot remove blocks: after TsdfMap::clear() the publisher sends a snapshot.
Status makeUpdate(const TsdfMap& map, uint64_t since_stamp, uint64_t sequence, bool snapshot, MapUpdate* update);

enum class ApplyResult {
  kApplied,       // the mirror now holds the state as of update.sequence
  kIgnored,       // a duplicate or older incremental update: nothing applied, nothing to do
  kNeedSnapshot,  // a sequence gap, or no snapshot yet: nothing applied; ask the publisher for one
  kIncompatible,  // voxel size, bounds, w_th or the mirror's block cap disagree: nothing applied
  kMalformed,     // bad arrays, values or block indices: nothing applied
};

const char* toString(ApplyResult result);

struct MirrorCounters {
  uint64_t applied = 0;        // updates applied (snapshots included)
  uint64_t snapshots = 0;      // snapshots applied
  uint64_t gaps = 0;           // kNeedSnapshot answers
  uint64_t ignored = 0;        // kIgnored answers
  uint64_t incompatible = 0;   // kIncompatible answers
  uint64_t malformed = 0;      // kMalformed answers
};

// A ROS-free copy of a publisher's TsdfMap, kept current by applying its
// MapUpdates in sequence. Every update is validated completely before any of
// it is applied, so a refused update leaves the mirror exactly as it was.
// Sequence rules:
//  - a snapshot always applies (it heals any gap and a restarted publisher),
//    and the next incremental update expected is snapshot.sequence + 1
//  - an incremental update applies iff its sequence is the last one + 1
//  - a later sequence, or any incremental update before the first snapshot
//    (a late joiner), answers kNeedSnapshot
//  - a duplicate or older sequence answers kIgnored, except that more than
//    kStaleRunLimit of them in a row (the publisher restarted its count)
//    answer kNeedSnapshot
// Applied blocks whose voxels differ from the mirror's (or that are new) get a
// fresh change stamp of the mirror's map, so its consumers poll
// map().blocksChangedSince() as they would on the mapper's map. A snapshot
// that lacks blocks the mirror holds clears the mirror's map first and counts
// a reset: consumers that cache per-block results rebuild when resets()
// changes. Not thread-safe: apply() and readers of map() must not overlap.
class MapMirror {
 public:
  static constexpr int kStaleRunLimit = 3;

  // `config` is the map configuration shared by all nodes and must validate():
  // updates must match its voxel_size, bounds and w_th bit for bit.
  explicit MapMirror(const TsdfConfig& config);

  ApplyResult apply(const MapUpdate& update);

  const TsdfMap& map() const { return map_; }
  // A snapshot has been applied since construction.
  bool synced() const { return synced_; }
  // Sequence of the last applied update (meaningful once synced()).
  uint64_t lastSequence() const { return last_sequence_; }
  uint64_t resets() const { return resets_; }
  const MirrorCounters& counters() const { return counters_; }
  // Why the last refused update was refused ("" after an applied one).
  const std::string& lastError() const { return last_error_; }

 private:
  Status checkHeader(const MapUpdate& update, ApplyResult* result) const;
  Status checkBlocks(const MapUpdate& update) const;
  ApplyResult refuse(ApplyResult result, const std::string& why);
  void applyBlocks(const MapUpdate& update);

  TsdfMap map_;
  bool synced_ = false;
  uint64_t last_sequence_ = 0;
  int stale_run_ = 0;
  uint64_t resets_ = 0;
  MirrorCounters counters_;
  std::string last_error_;
};

}  // namespace surface_nbv
