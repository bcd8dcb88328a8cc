#include "surface_nbv/map/map_update.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

using namespace surface_nbv;

namespace {

// 32 x 32 x 16 voxels: a 4 x 4 x 2 block grid.
TsdfConfig smallConfig() {
  TsdfConfig config;
  config.voxel_size = 0.25;
  config.w_th = 0.3f;
  config.bounds = AlignedBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(8, 8, 4));
  return config;
}

// Writes seeded values into `block` and stamps it, as an integrator would.
void scribble(TsdfMap* map, const Eigen::Vector3i& index, uint32_t seed) {
  TsdfBlock* block = map->allocateBlock(index);
  ASSERT_NE(block, nullptr);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> phi(-0.75f, 0.75f), w(0.0f, 5.0f);
  for (TsdfVoxel& v : block->voxels) {
    v.phi = phi(rng);
    v.w = w(rng);
  }
  block->voxels[0].phi = -0.0f;  // must survive bit for bit
  block->voxels[1].w = std::numeric_limits<float>::denorm_min();
  block->change_stamp = map->beginChange();
}

void expectSameMap(const TsdfMap& expected, const TsdfMap& actual) {
  ASSERT_EQ(expected.numBlocks(), actual.numBlocks());
  for (const auto& b : expected.blocks()) {
    const TsdfBlock* other = actual.block(b->index);
    ASSERT_NE(other, nullptr) << "missing block " << b->index.transpose();
    EXPECT_EQ(std::memcmp(b->voxels.data(), other->voxels.data(), sizeof(b->voxels)), 0)
        << "voxels differ in block " << b->index.transpose();
  }
}

MapUpdate update(const TsdfMap& map, uint64_t since, uint64_t sequence, bool snapshot) {
  MapUpdate u;
  EXPECT_TRUE(makeUpdate(map, since, sequence, snapshot, &u).ok());
  return u;
}

// A publisher with a map, a sequence counter and the stamp of its last update.
struct Publisher {
  TsdfMap map{smallConfig()};
  uint64_t sequence = 0;
  uint64_t since = 0;

  MapUpdate next(bool snapshot = false) {
    const uint64_t now = map.changeCounter();
    MapUpdate u = update(map, since, ++sequence, snapshot);
    since = now;
    return u;
  }
};

}  // namespace

TEST(MapUpdate, SnapshotCarriesEveryBlockAndTheMapHeader) {
  Publisher pub;
  scribble(&pub.map, {0, 0, 0}, 1);
  scribble(&pub.map, {3, 2, 1}, 2);
  const MapUpdate u = pub.next(true);
  EXPECT_TRUE(u.snapshot);
  EXPECT_EQ(u.sequence, 1u);
  EXPECT_EQ(u.voxel_size, 0.25);
  EXPECT_EQ(u.w_th, 0.3f);
  EXPECT_EQ(u.bounds.max, Eigen::Vector3d(8, 8, 4));
  ASSERT_EQ(u.blocks.size(), 2u);
  EXPECT_EQ(u.blocks[1].index, Eigen::Vector3i(3, 2, 1));
  ASSERT_EQ(u.blocks[1].phi.size(), static_cast<size_t>(kBlockVoxels));
  EXPECT_EQ(u.blocks[1].phi[TsdfBlock::linear(1, 2, 3)], pub.map.block({3, 2, 1})->at(1, 2, 3).phi);
  EXPECT_FALSE(makeUpdate(pub.map, 0, 1, true, nullptr).ok());
}

TEST(MapUpdate, IncrementalUpdatesCarryOnlyChangedBlocks) {
  Publisher pub;
  for (int i = 0; i < 4; ++i) scribble(&pub.map, {i, 0, 0}, 10 + i);
  EXPECT_EQ(pub.next(true).blocks.size(), 4u);
  EXPECT_TRUE(pub.next().blocks.empty());
  scribble(&pub.map, {2, 0, 0}, 20);
  scribble(&pub.map, {1, 3, 1}, 21);
  const MapUpdate u = pub.next();
  ASSERT_EQ(u.blocks.size(), 2u);
  EXPECT_EQ(u.blocks[0].index, Eigen::Vector3i(2, 0, 0));
  EXPECT_EQ(u.blocks[1].index, Eigen::Vector3i(1, 3, 1));
  EXPECT_FALSE(u.snapshot);
  EXPECT_EQ(pub.next(true).blocks.size(), 5u);
}

TEST(MapMirror, RoundTripIsBitIdenticalAndStampsOnlyChangedBlocks) {
  Publisher pub;
  for (int i = 0; i < 8; ++i) scribble(&pub.map, {i % 4, i / 4, i % 2}, 100 + i);
  MapMirror mirror(smallConfig());
  EXPECT_FALSE(mirror.synced());
  ASSERT_EQ(mirror.apply(pub.next(true)), ApplyResult::kApplied) << mirror.lastError();
  EXPECT_TRUE(mirror.synced());
  expectSameMap(pub.map, mirror.map());

  for (int round = 0; round < 5; ++round) {
    const uint64_t before = mirror.map().changeCounter();
    scribble(&pub.map, {round % 4, 3, 1}, 200 + round);
    scribble(&pub.map, {1, 0, 1}, 300 + round);
    ASSERT_EQ(mirror.apply(pub.next()), ApplyResult::kApplied) << mirror.lastError();
    expectSameMap(pub.map, mirror.map());
    const std::vector<Eigen::Vector3i> changed = mirror.map().blocksChangedSince(before);
    ASSERT_EQ(changed.size(), 2u);
  }
  EXPECT_EQ(mirror.lastSequence(), 6u);
  EXPECT_EQ(mirror.counters().applied, 6u);
  EXPECT_EQ(mirror.counters().snapshots, 1u);

  // Re-sent unchanged content stamps nothing, so consumers redo no work.
  const uint64_t before = mirror.map().changeCounter();
  ASSERT_EQ(mirror.apply(pub.next(true)), ApplyResult::kApplied);
  EXPECT_TRUE(mirror.map().blocksChangedSince(before).empty());
  EXPECT_EQ(mirror.resets(), 0u);
}

TEST(MapMirror, GapAsksForSnapshotAndTheSnapshotHeals) {
  Publisher pub;
  scribble(&pub.map, {0, 0, 0}, 1);
  MapMirror mirror(smallConfig());
  ASSERT_EQ(mirror.apply(pub.next(true)), ApplyResult::kApplied);
  scribble(&pub.map, {1, 0, 0}, 2);
  ASSERT_EQ(mirror.apply(pub.next()), ApplyResult::kApplied);

  scribble(&pub.map, {2, 0, 0}, 3);
  pub.next();  // sequence 3 is lost
  scribble(&pub.map, {3, 0, 0}, 4);
  EXPECT_EQ(mirror.apply(pub.next()), ApplyResult::kNeedSnapshot);
  EXPECT_NE(mirror.lastError().find("expected update 3, got 4"), std::string::npos) << mirror.lastError();
  EXPECT_EQ(mirror.map().numBlocks(), 2u);  // nothing of update 4 applied
  EXPECT_EQ(mirror.lastSequence(), 2u);
  scribble(&pub.map, {0, 1, 0}, 5);
  EXPECT_EQ(mirror.apply(pub.next()), ApplyResult::kNeedSnapshot);
  EXPECT_EQ(mirror.counters().gaps, 2u);

  ASSERT_EQ(mirror.apply(pub.next(true)), ApplyResult::kApplied);
  expectSameMap(pub.map, mirror.map());
  scribble(&pub.map, {0, 2, 0}, 6);
  ASSERT_EQ(mirror.apply(pub.next()), ApplyResult::kApplied);
  expectSameMap(pub.map, mirror.map());
  EXPECT_EQ(mirror.lastSequence(), 7u);
}

TEST(MapMirror, LateJoinerWaitsForASnapshot) {
  Publisher pub;
  scribble(&pub.map, {0, 0, 0}, 1);
  pub.next(true);
  scribble(&pub.map, {1, 1, 1}, 2);
  pub.next();
  MapMirror mirror(smallConfig());
  scribble(&pub.map, {2, 2, 1}, 3);
  EXPECT_EQ(mirror.apply(pub.next()), ApplyResult::kNeedSnapshot);
  EXPECT_FALSE(mirror.synced());
  EXPECT_EQ(mirror.map().numBlocks(), 0u);
  ASSERT_EQ(mirror.apply(pub.next(true)), ApplyResult::kApplied);
  EXPECT_TRUE(mirror.synced());
  expectSameMap(pub.map, mirror.map());

  // Even update 1 is refused without a snapshot: the mirror cannot know what came before.
  MapMirror early(smallConfig());
  MapUpdate first = update(pub.map, 0, 1, false);
  EXPECT_EQ(early.apply(first), ApplyResult::kNeedSnapshot);
  EXPECT_EQ(early.map().numBlocks(), 0u);
}

TEST(MapMirror, DuplicatesAreIgnoredAndARestartedCountAsksForASnapshot) {
  Publisher pub;
  scribble(&pub.map, {0, 0, 0}, 1);
  MapMirror mirror(smallConfig());
  ASSERT_EQ(mirror.apply(pub.next(true)), ApplyResult::kApplied);
  scribble(&pub.map, {1, 0, 0}, 2);
  const MapUpdate second = pub.next();
  ASSERT_EQ(mirror.apply(second), ApplyResult::kApplied);

  MapUpdate stale = second;
  stale.blocks[0].phi.assign(kBlockVoxels, 0.5f);  // would change the mirror if applied
  EXPECT_EQ(mirror.apply(stale), ApplyResult::kIgnored);
  stale.sequence = 1;
  EXPECT_EQ(mirror.apply(stale), ApplyResult::kIgnored);
  expectSameMap(pub.map, mirror.map());
  EXPECT_EQ(mirror.counters().ignored, 2u);
  EXPECT_EQ(mirror.apply(stale), ApplyResult::kIgnored);
  EXPECT_EQ(mirror.apply(stale), ApplyResult::kNeedSnapshot);  // 4 in a row: a restarted publisher
  expectSameMap(pub.map, mirror.map());

  // A snapshot is always taken, even with a smaller sequence; counting restarts there.
  Publisher restarted;
  scribble(&restarted.map, {3, 3, 0}, 9);
  ASSERT_EQ(mirror.apply(restarted.next(true)), ApplyResult::kApplied);
  expectSameMap(restarted.map, mirror.map());
  EXPECT_EQ(mirror.lastSequence(), 1u);
  EXPECT_EQ(mirror.resets(), 1u);  // the old blocks were dropped
}

TEST(MapMirror, MalformedUpdatesAreRejectedWhole) {
  Publisher pub;
  scribble(&pub.map, {0, 0, 0}, 1);
  MapMirror mirror(smallConfig());
  ASSERT_EQ(mirror.apply(pub.next(true)), ApplyResult::kApplied);
  scribble(&pub.map, {0, 0, 0}, 2);
  scribble(&pub.map, {1, 2, 1}, 3);
  const MapUpdate good = pub.next();
  ASSERT_EQ(good.blocks.size(), 2u);

  std::vector<std::pair<std::string, MapUpdate>> bad;
  auto variant = [&](const std::string& name, auto&& edit) {
    MapUpdate u = good;
    edit(u);
    bad.emplace_back(name, u);
  };
  // Every variant breaks only the second block: the first must not be applied either.
  variant("short phi", [](MapUpdate& u) { u.blocks[1].phi.pop_back(); });
  variant("long w", [](MapUpdate& u) { u.blocks[1].w.push_back(1.0f); });
  variant("empty arrays", [](MapUpdate& u) { u.blocks[1].phi.clear(); u.blocks[1].w.clear(); });
  variant("NaN phi", [](MapUpdate& u) { u.blocks[1].phi[7] = std::nanf(""); });
  variant("infinite w", [](MapUpdate& u) { u.blocks[1].w[7] = std::numeric_limits<float>::infinity(); });
  variant("negative w", [](MapUpdate& u) { u.blocks[1].w[511] = -1e-6f; });
  variant("negative index", [](MapUpdate& u) { u.blocks[1].index = Eigen::Vector3i(-1, 0, 0); });
  variant("index past grid", [](MapUpdate& u) { u.blocks[1].index = Eigen::Vector3i(0, 0, 2); });
  variant("duplicate block", [](MapUpdate& u) { u.blocks[1].index = u.blocks[0].index; });
  variant("NaN voxel size", [](MapUpdate& u) { u.voxel_size = std::nan(""); });
  variant("infinite bounds", [](MapUpdate& u) { u.bounds.max.x() = std::numeric_limits<double>::infinity(); });

  const uint64_t stamp = mirror.map().changeCounter();
  for (const auto& [name, u] : bad) {
    EXPECT_EQ(mirror.apply(u), ApplyResult::kMalformed) << name;
    EXPECT_FALSE(mirror.lastError().empty()) << name;
    EXPECT_EQ(mirror.map().numBlocks(), 1u) << name;
    EXPECT_EQ(mirror.map().changeCounter(), stamp) << name;
    EXPECT_EQ(mirror.lastSequence(), 1u) << name;
  }
  EXPECT_EQ(mirror.counters().malformed, bad.size());
  MapUpdate snapshot_bad = bad[0].second;
  snapshot_bad.snapshot = true;
  EXPECT_EQ(mirror.apply(snapshot_bad), ApplyResult::kMalformed);

  ASSERT_EQ(mirror.apply(good), ApplyResult::kApplied) << mirror.lastError();
  expectSameMap(pub.map, mirror.map());
}

TEST(MapMirror, IncompatibleUpdatesAreRejected) {
  Publisher pub;
  scribble(&pub.map, {0, 0, 0}, 1);
  scribble(&pub.map, {1, 0, 0}, 2);
  const MapUpdate good = pub.next(true);
  MapMirror mirror(smallConfig());

  MapUpdate u = good;
  u.voxel_size = 0.2;
  EXPECT_EQ(mirror.apply(u), ApplyResult::kIncompatible);
  EXPECT_NE(mirror.lastError().find("voxel_size"), std::string::npos);
  u = good;
  u.bounds.min.z() = -1.0;
  EXPECT_EQ(mirror.apply(u), ApplyResult::kIncompatible);
  u = good;
  u.w_th = 0.5f;
  EXPECT_EQ(mirror.apply(u), ApplyResult::kIncompatible);
  EXPECT_EQ(mirror.counters().incompatible, 3u);
  EXPECT_FALSE(mirror.synced());
  EXPECT_EQ(mirror.map().numBlocks(), 0u);

  TsdfConfig capped = smallConfig();
  capped.max_blocks = 1;
  MapMirror small(capped);
  EXPECT_EQ(small.apply(good), ApplyResult::kIncompatible);
  EXPECT_NE(small.lastError().find("max_blocks"), std::string::npos);
  EXPECT_EQ(small.map().numBlocks(), 0u);
  EXPECT_EQ(small.map().refusedAllocations(), 0u);

  ASSERT_EQ(mirror.apply(good), ApplyResult::kApplied);
  expectSameMap(pub.map, mirror.map());
}

TEST(MapMirror, SnapshotAfterAClearedMapDropsOldBlocks) {
  Publisher pub;
  scribble(&pub.map, {0, 0, 0}, 1);
  scribble(&pub.map, {1, 1, 1}, 2);
  MapMirror mirror(smallConfig());
  ASSERT_EQ(mirror.apply(pub.next(true)), ApplyResult::kApplied);
  pub.map.clear();
  scribble(&pub.map, {1, 1, 1}, 3);
  const uint64_t before = mirror.map().changeCounter();
  ASSERT_EQ(mirror.apply(pub.next(true)), ApplyResult::kApplied);
  expectSameMap(pub.map, mirror.map());
  EXPECT_EQ(mirror.resets(), 1u);
  EXPECT_EQ(mirror.map().blocksChangedSince(before).size(), 1u);
  EXPECT_EQ(std::string(toString(ApplyResult::kNeedSnapshot)), "need_snapshot");
}
