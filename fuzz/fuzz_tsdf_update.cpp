// libFuzzer target: a serialised surface_nbv/TsdfUpdate, as it arrives on
// tsdf/update, deserialised with ros::serialization, converted with
// fromUpdateMsg and applied to a MapMirror that already holds a snapshot
// (sequence 1) of a seeded map, as map_feed does. A refused update must leave
// the mirror's digest unchanged; an applied one must be held bit for bit and
// keep the map sound.
//
// ros::serialization resizes a vector to its wire length before it checks
// that the bytes are there, so a 4-byte length can ask for gigabytes (a
// roscpp subscriber has the same exposure; see docs/reliability.md). The
// wire walk below refuses such inputs first, as a truncated message, so the
// fuzzer explores this package's code instead of that allocation.
#include <random>
#include <vector>

#include <ros/serialization.h>

#include "../test/fuzz/map_digest.h"
#include "fuzz_support.h"
#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/ros/map_conversions.h"

using namespace surface_nbv;
using namespace surface_nbv::fuzz;

namespace {

// Walks the wire layout of TsdfUpdate; true if every length fits the bytes.
bool wireLengthsFit(const uint8_t* data, size_t size) {
  ByteReader in(data, size);
  auto skip = [&in](size_t n) {
    if (in.restSize() < n) return false;
    for (size_t i = 0; i < n; ++i) in.take<uint8_t>();
    return true;
  };
  auto array = [&in, &skip](size_t element) {
    if (in.restSize() < 4) return false;
    const uint64_t n = in.take<uint32_t>();
    return n * element <= in.restSize() && skip(static_cast<size_t>(n * element));
  };
  if (!skip(12) || !array(1)) return false;  // header: seq, stamp, frame_id
  if (!skip(8 + 1 + 8 + 4 + 24 + 24) || in.restSize() < 4) return false;
  const uint64_t blocks = in.take<uint32_t>();
  if (blocks * 20 > in.restSize()) return false;  // a block takes at least 20 bytes
  for (uint64_t b = 0; b < blocks; ++b) {
    if (!skip(12) || !array(4) || !array(4)) return false;
  }
  return true;
}

TsdfConfig mirrorConfig() {
  TsdfConfig config;
  config.voxel_size = 0.25;
  config.w_th = 0.3f;
  config.bounds = AlignedBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(8, 8, 4));
  config.max_blocks = 24;
  return config;
}

// The snapshot (sequence 1) of three seeded blocks that every mirror starts from.
const MapUpdate& firstSnapshot() {
  static const MapUpdate snapshot = [] {
    TsdfMap map(mirrorConfig());
    std::mt19937 rng(11);
    for (int b = 0; b < 3; ++b) {
      TsdfBlock* block = map.allocateBlock(Eigen::Vector3i(b, b % 2, 0));
      for (TsdfVoxel& v : block->voxels) {
        v.phi = std::uniform_real_distribution<float>(-0.5f, 0.5f)(rng);
        v.w = std::uniform_real_distribution<float>(0.0f, 3.0f)(rng);
      }
      block->change_stamp = map.beginChange();
    }
    MapUpdate u;
    makeUpdate(map, 0, 1, true, &u);
    return u;
  }();
  return snapshot;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (!wireLengthsFit(data, size)) return 0;
  surface_nbv::TsdfUpdate msg;
  try {
    ros::serialization::IStream stream(const_cast<uint8_t*>(data), static_cast<uint32_t>(size));
    ros::serialization::deserialize(stream, msg);
  } catch (const ros::serialization::StreamOverrunException&) {
    return 0;
  }
  MapMirror mirror(mirrorConfig());
  FUZZ_CHECK(mirror.apply(firstSnapshot()) == ApplyResult::kApplied, "the first snapshot was refused");
  MapUpdate update;
  fromUpdateMsg(msg, &update);
  const uint64_t before = mirrorDigest(mirror);
  const ApplyResult result = mirror.apply(update);
  if (result != ApplyResult::kApplied) {
    FUZZ_CHECK(mirrorDigest(mirror) == before, std::string("a ") + toString(result) + " update changed the mirror");
    FUZZ_CHECK(!mirror.lastError().empty(), "a refusal without a reason");
    return 0;
  }
  FUZZ_CHECK(mapFault(mirror.map()).empty(), mapFault(mirror.map()));
  FUZZ_CHECK(mapHoldsUpdate(mirror.map(), update), "the mirror lost part of an update");
  FUZZ_CHECK(mirror.lastSequence() == update.sequence, "sequence");
  if (update.snapshot) FUZZ_CHECK(mirror.map().numBlocks() == update.blocks.size(), "a snapshot left stale blocks");
  return 0;
}
