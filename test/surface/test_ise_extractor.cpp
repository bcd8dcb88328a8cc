#include "surface_nbv/surface/ise_extractor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "surface_test_maps.h"

using namespace surface_nbv;
using namespace surface_nbv::test;

namespace {

using VoxelSet = std::set<std::tuple<int, int, int>>;

VoxelSet asSet(const std::vector<Eigen::Vector3i>& voxels) {
  VoxelSet out;
  for (const Eigen::Vector3i& v : voxels) out.insert({v.x(), v.y(), v.z()});
  return out;
}

// Brute force over the map, eq. 1 read literally (outside the grid is
// neither unknown nor occupied).
VoxelSet bruteForce(const TsdfMap& map) {
  const Eigen::Vector3i& g = map.gridVoxels();
  auto state = [&](const Eigen::Vector3i& v) {
    return map.voxelInBounds(v) ? static_cast<int>(map.state(v)) : -1;
  };
  VoxelSet out;
  for (int z = 0; z < g.z(); ++z)
    for (int y = 0; y < g.y(); ++y)
      for (int x = 0; x < g.x(); ++x) {
        const Eigen::Vector3i v(x, y, z);
        if (map.state(v) != VoxelState::kFree) continue;
        bool unknown = false, occupied = false;
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const int nonzero = (dx != 0) + (dy != 0) + (dz != 0);
              const int s = state(v + Eigen::Vector3i(dx, dy, dz));
              if (nonzero == 1 && s == static_cast<int>(VoxelState::kUnknown)) unknown = true;
              if (nonzero >= 1 && nonzero <= 2 && s == static_cast<int>(VoxelState::kOccupied)) occupied = true;
            }
        if (unknown && occupied) out.insert({x, y, z});
      }
  return out;
}

// A wall at x = 12 scanned for y < 12 over the whole height: free space in
// front of the scanned half (4 <= x < 12), everything else unknown.
TsdfMap halfScannedWall() {
  TsdfMap map(gridConfig(Eigen::Vector3i(24, 24, 16)));
  fillBox(&map, Eigen::Vector3i(12, 0, 0), Eigen::Vector3i(13, 12, 16), VoxelState::kOccupied);
  fillBox(&map, Eigen::Vector3i(4, 0, 0), Eigen::Vector3i(12, 12, 16), VoxelState::kFree);
  return map;
}

}  // namespace

TEST(IseExtractor, HalfScannedWallGivesTheKnownUnknownBoundaryExactly) {
  const TsdfMap map = halfScannedWall();
  IseExtractor extractor;
  extractor.update(map);
  VoxelSet expected;
  for (int z = 0; z < 16; ++z) expected.insert({11, 11, z});
  EXPECT_EQ(asSet(extractor.ises()), expected);
  EXPECT_EQ(extractor.size(), 16u);
  // Scanned: the rest of the column in front of the wall, x = 11, y < 11.
  EXPECT_EQ(extractor.scannedCount(), 11u * 16u);
  EXPECT_TRUE(extractor.isIse(Eigen::Vector3i(11, 11, 3)));
  EXPECT_FALSE(extractor.isIse(Eigen::Vector3i(10, 11, 3)));
  EXPECT_FALSE(extractor.isIse(Eigen::Vector3i(11, 10, 3)));
}

TEST(IseExtractor, FullyScannedClosedBoxHasNoIse) {
  // A hollow 6^3 box (its inside never seen), known free all around it.
  TsdfMap map(gridConfig(Eigen::Vector3i(16, 16, 16)));
  fillAll(&map, VoxelState::kFree);
  fillBox(&map, Eigen::Vector3i(5, 5, 5), Eigen::Vector3i(11, 11, 11), VoxelState::kOccupied);
  fillBox(&map, Eigen::Vector3i(6, 6, 6), Eigen::Vector3i(10, 10, 10), VoxelState::kUnknown);
  IseExtractor extractor;
  extractor.update(map);
  EXPECT_EQ(extractor.size(), 0u);
  EXPECT_TRUE(extractor.ises().empty());
  // Every free voxel with an occupied 18-neighbour is scanned: 6 faces and 12 edges of the box.
  EXPECT_EQ(extractor.scannedCount(), 6u * 36u + 12u * 6u);
}

TEST(IseExtractor, OpeningAHoleInTheBoxCreatesIsesAroundIt) {
  TsdfMap map(gridConfig(Eigen::Vector3i(16, 16, 16)));
  fillAll(&map, VoxelState::kFree);
  fillBox(&map, Eigen::Vector3i(5, 5, 5), Eigen::Vector3i(11, 11, 11), VoxelState::kOccupied);
  fillBox(&map, Eigen::Vector3i(6, 6, 6), Eigen::Vector3i(10, 10, 10), VoxelState::kUnknown);
  IseExtractor extractor;
  extractor.update(map);
  // One face voxel becomes unknown (an unscanned patch on the +x face).
  setState(&map, Eigen::Vector3i(10, 7, 7), VoxelState::kUnknown);
  const IseUpdateStats stats = extractor.update(map);
  EXPECT_FALSE(stats.full);
  EXPECT_EQ(asSet(extractor.ises()), VoxelSet({{11, 7, 7}}));
  EXPECT_EQ(stats.ises_added, 1u);
  EXPECT_EQ(asSet(extractor.ises()), bruteForce(map));
}

TEST(IseExtractor, MatchesBruteForceOnRandomMaps) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 5; ++trial) {
    TsdfMap map(gridConfig(Eigen::Vector3i(21, 19, 17)));  // not whole blocks: partial edge blocks
    std::uniform_int_distribution<int> pick(0, 9);
    const Eigen::Vector3i& g = map.gridVoxels();
    for (int z = 0; z < g.z(); ++z)
      for (int y = 0; y < g.y(); ++y)
        for (int x = 0; x < g.x(); ++x) {
          const int p = pick(rng);
          if (p < 2) continue;  // unallocated or never written: unknown
          setState(&map, Eigen::Vector3i(x, y, z),
                   p < 4 ? VoxelState::kUnknown : (p < 6 ? VoxelState::kOccupied : VoxelState::kFree));
        }
    IseExtractor extractor;
    extractor.update(map);
    const VoxelSet expected = bruteForce(map);
    EXPECT_GT(expected.size(), 100u);
    EXPECT_EQ(asSet(extractor.ises()), expected);
  }
}

TEST(IseExtractor, IncrementalUpdatesEqualFullExtraction) {
  std::mt19937 rng(11);
  TsdfMap map(gridConfig(Eigen::Vector3i(40, 40, 24)));
  IseExtractor incremental(2);
  incremental.update(map);
  std::uniform_int_distribution<int> coord(0, 39), height(0, 23), state(0, 2), size(1, 6);
  for (int step = 0; step < 30; ++step) {
    // A random box of one state, as a frame would write it.
    const Eigen::Vector3i lo(coord(rng), coord(rng), height(rng));
    const Eigen::Vector3i hi = (lo + Eigen::Vector3i(size(rng), size(rng), size(rng))).cwiseMin(map.gridVoxels());
    fillBox(&map, lo, hi, static_cast<VoxelState>(state(rng)));
    const IseUpdateStats stats = incremental.update(map);
    EXPECT_FALSE(stats.full);
    EXPECT_LE(stats.blocks_examined, 27 * stats.blocks_changed);
    IseExtractor full(1);
    full.rebuild(map);
    ASSERT_EQ(incremental.ises(), full.ises()) << "step " << step;
    ASSERT_EQ(incremental.size(), full.size());
    ASSERT_EQ(incremental.scannedCount(), full.scannedCount());
  }
  EXPECT_EQ(asSet(incremental.ises()), bruteForce(map));
}

TEST(IseExtractor, ReexaminesOnlyChangedBlocksAndTheirNeighbours) {
  TsdfMap map(gridConfig(Eigen::Vector3i(40, 40, 40)));  // 5^3 blocks
  fillAll(&map, VoxelState::kFree);
  IseExtractor extractor;
  EXPECT_TRUE(extractor.update(map).full);
  IseUpdateStats idle = extractor.update(map);
  EXPECT_EQ(idle.blocks_changed, 0u);
  EXPECT_EQ(idle.blocks_examined, 0u);
  setState(&map, Eigen::Vector3i(20, 20, 20), VoxelState::kOccupied);  // block (2, 2, 2): interior
  IseUpdateStats interior = extractor.update(map);
  EXPECT_EQ(interior.blocks_changed, 1u);
  EXPECT_EQ(interior.blocks_examined, 27u);
  setState(&map, Eigen::Vector3i(0, 0, 0), VoxelState::kOccupied);  // block (0, 0, 0): a corner
  IseUpdateStats corner = extractor.update(map);
  EXPECT_EQ(corner.blocks_changed, 1u);
  EXPECT_EQ(corner.blocks_examined, 8u);
}

TEST(IseExtractor, ClearedMapLosesItsIses) {
  TsdfMap map = halfScannedWall();
  IseExtractor extractor;
  extractor.update(map);
  ASSERT_EQ(extractor.size(), 16u);
  map.clear();
  extractor.update(map);
  EXPECT_EQ(extractor.size(), 0u);
  EXPECT_EQ(extractor.scannedCount(), 0u);
  // A snapshot with as many blocks elsewhere: the vanished ones are noticed too.
  TsdfMap other(map.config());
  fillBox(&other, Eigen::Vector3i(12, 0, 0), Eigen::Vector3i(13, 12, 16), VoxelState::kOccupied);
  fillBox(&other, Eigen::Vector3i(4, 0, 0), Eigen::Vector3i(12, 12, 16), VoxelState::kFree);
  map.adoptBlocks(&other);
  extractor.update(map);
  ASSERT_EQ(extractor.size(), 16u);
  TsdfMap moved(map.config());
  fillBox(&moved, Eigen::Vector3i(12, 12, 0), Eigen::Vector3i(13, 24, 16), VoxelState::kOccupied);
  fillBox(&moved, Eigen::Vector3i(4, 12, 0), Eigen::Vector3i(12, 24, 16), VoxelState::kFree);
  map.adoptBlocks(&moved);
  extractor.update(map);
  EXPECT_EQ(asSet(extractor.ises()), bruteForce(map));
}

TEST(IseExtractor, ThreadCountDoesNotChangeTheResult) {
  std::mt19937 rng(5);
  TsdfMap map(gridConfig(Eigen::Vector3i(32, 32, 32)));
  std::uniform_int_distribution<int> pick(0, 3);
  for (int z = 0; z < 32; ++z)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) setState(&map, Eigen::Vector3i(x, y, z), static_cast<VoxelState>(pick(rng) % 3));
  IseExtractor one(1), two(2);
  one.update(map);
  two.update(map);
  EXPECT_EQ(one.ises(), two.ises());
  EXPECT_EQ(one.scannedCount(), two.scannedCount());
}
