#include "surface_nbv/map/collision_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace surface_nbv;

namespace {

// 8 x 8 x 8 m: 32^3 voxels of 0.25 m, 4^3 blocks.
TsdfConfig mapConfig(double voxel_size = 0.25) {
  TsdfConfig c;
  c.voxel_size = voxel_size;
  c.bounds = AlignedBox(Eigen::Vector3d(-4, -4, 0), Eigen::Vector3d(4, 4, 8));
  return c;
}

CollisionConfig collisionConfig() {
  CollisionConfig c;
  c.min_cell_size = 0.0;
  c.bounds_are_obstacle = false;
  return c;
}

void setVoxel(TsdfMap* map, const Eigen::Vector3i& v, VoxelState state) {
  TsdfVoxel* voxel = map->allocateVoxel(v);
  ASSERT_NE(voxel, nullptr);
  voxel->w = state == VoxelState::kUnknown ? 0.0f : 1.0f;
  voxel->phi = state == VoxelState::kOccupied ? -0.1f : 0.2f;
  map->mutableBlock(TsdfMap::blockOfVoxel(v))->change_stamp = map->beginChange();
}

void fillKnownFree(TsdfMap* map) {
  const Eigen::Vector3i& g = map->gridVoxels();
  for (int z = 0; z < g.z(); ++z)
    for (int y = 0; y < g.y(); ++y)
      for (int x = 0; x < g.x(); ++x) setVoxel(map, Eigen::Vector3i(x, y, z), VoxelState::kFree);
}

// Distance from p to the axis-aligned cube [lo, lo + size]^3.
double cubeDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, double size) {
  const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(size);
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm();
}

Eigen::Vector3d randomPoint(std::mt19937* rng, const AlignedBox& box) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  return box.min + Eigen::Vector3d(u(*rng), u(*rng), u(*rng)).cwiseProduct(box.size());
}

// Every cell's transform value and distance at random points agree.
void expectSameAsScratch(const CollisionMap& incremental, const TsdfMap& map, const CollisionConfig& config) {
  EXPECT_TRUE(incremental.cacheMatchesTransform());
  const CollisionMap scratch(map, config);
  const Eigen::Vector3i& g = scratch.gridCells();
  int mismatches = 0;
  for (int z = 0; z < g.z(); ++z)
    for (int y = 0; y < g.y(); ++y)
      for (int x = 0; x < g.x(); ++x) {
        const Eigen::Vector3i c(x, y, z);
        if (incremental.isObstacleCell(c) != scratch.isObstacleCell(c) ||
            incremental.cellCentreDistance(c) != scratch.cellCentreDistance(c)) {
          ++mismatches;
        }
      }
  EXPECT_EQ(mismatches, 0);
  std::mt19937 rng(7);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d p = randomPoint(&rng, map.config().bounds);
    ASSERT_NEAR(incremental.distance(p), scratch.distance(p), scratch.cellSize()) << p.transpose();
  }
}

}  // namespace

TEST(CollisionConfig, ValidateNamesTheBadKey) {
  EXPECT_TRUE(CollisionConfig().validate().ok());
  CollisionConfig c;
  c.max_distance = 1.5;
  EXPECT_NE(c.validate().message().find("max_distance"), std::string::npos);
  c.max_distance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(c.validate().ok());
  c = CollisionConfig();
  c.min_cell_size = -0.1;
  EXPECT_NE(c.validate().message().find("min_cell_size"), std::string::npos);
}

TEST(CollisionMap, CellSizeIsAMultipleOfTheVoxel) {
  CollisionConfig c;
  EXPECT_EQ(CollisionMap::voxelsPerCellFor(0.3, c), 1);
  EXPECT_EQ(CollisionMap::voxelsPerCellFor(0.15, c), 2);
  EXPECT_EQ(CollisionMap::voxelsPerCellFor(0.1, c), 3);
  EXPECT_EQ(CollisionMap::voxelsPerCellFor(0.5, c), 1);
  c.min_cell_size = 0.0;
  EXPECT_EQ(CollisionMap::voxelsPerCellFor(0.15, c), 1);
  EXPECT_EQ(CollisionMap::voxelsPerCellFor(0.01, c), 2);  // 2 m in at most kMaxCapCells cells
  const TsdfMap map(mapConfig(0.15));
  const CollisionMap coll(map, CollisionConfig());
  EXPECT_DOUBLE_EQ(coll.cellSize(), 0.3);
  EXPECT_EQ(coll.gridCells(), Eigen::Vector3i(27, 27, 27));  // 54 voxels per axis
}

TEST(CollisionMap, SingleObstacleGivesEuclideanDistance) {
  TsdfMap map(mapConfig());
  fillKnownFree(&map);
  const Eigen::Vector3i o(13, 17, 11);
  setVoxel(&map, o, VoxelState::kOccupied);
  const CollisionMap coll(map, collisionConfig());
  const Eigen::Vector3d centre = map.voxelCenter(o);
  const Eigen::Vector3d lo = centre - Eigen::Vector3d::Constant(0.125);
  std::mt19937 rng(1);
  const AlignedBox near(centre - Eigen::Vector3d::Constant(2.5), centre + Eigen::Vector3d::Constant(2.5));
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector3d p = randomPoint(&rng, near);
    const double d = coll.distance(p);
    ASSERT_NEAR(d, std::min(2.0, cubeDistance(p, lo, 0.25)), 1e-9) << p.transpose();
    ASSERT_NEAR(d, std::min(2.0, (p - centre).norm()), 0.25) << p.transpose();
  }
  EXPECT_NEAR(coll.distance(centre + Eigen::Vector3d(1.0, 0, 0)), 0.875, 1e-12);
  EXPECT_NEAR(coll.cellCentreDistance(o + Eigen::Vector3i(4, 0, 0)), 1.0, 1e-12);
  EXPECT_EQ(coll.distance(centre), 0.0);
}

TEST(CollisionMap, CoarseCellsInflateBySubCell) {
  TsdfMap map(mapConfig(0.15));  // 0.3 m collision cells
  fillKnownFree(&map);
  const Eigen::Vector3i o(25, 26, 27);
  setVoxel(&map, o, VoxelState::kOccupied);
  CollisionConfig config;
  config.bounds_are_obstacle = false;
  const CollisionMap coll(map, config);
  ASSERT_EQ(coll.voxelsPerCell(), 2);
  const Eigen::Vector3d lo = map.voxelCenter(o) - Eigen::Vector3d::Constant(0.075);
  std::mt19937 rng(2);
  const AlignedBox near(lo - Eigen::Vector3d::Constant(2.5), lo + Eigen::Vector3d::Constant(2.5));
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector3d p = randomPoint(&rng, near);
    const double truth = std::min(2.0, cubeDistance(p, lo, 0.15));
    const double d = coll.distance(p);
    ASSERT_LE(d, truth + 1e-9) << p.transpose();
    ASSERT_GE(d, truth - coll.cellSize()) << p.transpose();
  }
}

TEST(CollisionMap, RandomObstaclesNeverUnderestimateAndStayWithinACell) {
  TsdfMap map(mapConfig());
  fillKnownFree(&map);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> idx(0, 31);
  std::vector<Eigen::Vector3d> cubes;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3i v(idx(rng), idx(rng), idx(rng));
    setVoxel(&map, v, VoxelState::kOccupied);
    cubes.push_back(map.voxelCenter(v) - Eigen::Vector3d::Constant(0.125));
  }
  const CollisionMap coll(map, collisionConfig());
  double worst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d p = randomPoint(&rng, map.config().bounds);
    double truth = 2.0;
    for (const Eigen::Vector3d& lo : cubes) truth = std::min(truth, cubeDistance(p, lo, 0.25));
    const double d = coll.distance(p);
    ASSERT_GE(d, truth - 1e-9) << p.transpose();
    worst = std::max(worst, d - truth);
  }
  EXPECT_LT(worst, coll.cellSize());
  std::printf("worst over-estimate: %.3f cell\n", worst / coll.cellSize());
}

TEST(CollisionMap, DistanceIsCappedAtMaxDistance) {
  TsdfMap map(mapConfig());
  fillKnownFree(&map);
  setVoxel(&map, Eigen::Vector3i(0, 0, 0), VoxelState::kOccupied);
  CollisionConfig config = collisionConfig();
  const CollisionMap coll(map, config);
  EXPECT_EQ(coll.distance(Eigen::Vector3d(2, 2, 5)), 2.0);
  config.max_distance = 3.0;
  const CollisionMap wide(map, config);
  EXPECT_EQ(wide.distance(Eigen::Vector3d(2, 2, 5)), 3.0);
  EXPECT_NEAR(wide.distance(Eigen::Vector3d(-3.75 + 2.5, -3.875, 0.125)), 2.5, 1e-12);
  std::mt19937 rng(4);
  for (int i = 0; i < 2000; ++i) {
    ASSERT_LE(coll.distance(randomPoint(&rng, map.config().bounds)), 2.0);
  }
}

TEST(CollisionMap, UnknownIsAnObstacleUnlessConfiguredOtherwise) {
  TsdfMap map(mapConfig());
  const CollisionMap empty(map, collisionConfig());
  EXPECT_EQ(empty.distance(Eigen::Vector3d(0, 0, 4)), 0.0);
  // A known free cube of 3 m around (0, 0, 4) in unknown space.
  for (int z = 10; z < 22; ++z)
    for (int y = 10; y < 22; ++y)
      for (int x = 10; x < 22; ++x) setVoxel(&map, Eigen::Vector3i(x, y, z), VoxelState::kFree);
  const CollisionMap coll(map, collisionConfig());
  EXPECT_NEAR(coll.distance(Eigen::Vector3d(0, 0, 4)), 1.5, 1e-12);
  EXPECT_NEAR(coll.distance(Eigen::Vector3d(1.2, 0, 4)), 0.3, 1e-12);
  CollisionConfig config = collisionConfig();
  config.unknown_is_obstacle = false;
  const CollisionMap optimistic(map, config);
  EXPECT_EQ(optimistic.distance(Eigen::Vector3d(0, 0, 4)), 2.0);
  EXPECT_EQ(optimistic.distance(Eigen::Vector3d(3.9, 3.9, 0.1)), 2.0);
}

TEST(CollisionMap, OutsideBoundsAndNonFiniteAreObstacles) {
  TsdfMap map(mapConfig());
  fillKnownFree(&map);
  CollisionConfig config = collisionConfig();
  const CollisionMap coll(map, config);
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(4.01, 0, 4), Eigen::Vector3d(0, -4.01, 4), Eigen::Vector3d(0, 0, -0.01),
                                   Eigen::Vector3d(0, 0, 8.5), Eigen::Vector3d(nan, 0, 4), Eigen::Vector3d(0, inf, 4),
                                   Eigen::Vector3d(-1e300, 0, 4)}) {
    EXPECT_EQ(coll.distance(p), 0.0) << p.transpose();
    EXPECT_FALSE(coll.isFree(p, 0.0)) << p.transpose();
  }
  EXPECT_EQ(coll.distance(Eigen::Vector3d(3.5, 0, 4)), 2.0);
  config.bounds_are_obstacle = true;
  const CollisionMap walled(map, config);
  EXPECT_NEAR(walled.distance(Eigen::Vector3d(3.5, 0, 4)), 0.5, 1e-12);
  EXPECT_NEAR(walled.distance(Eigen::Vector3d(0, 0, 0.25)), 0.25, 1e-12);
  EXPECT_EQ(walled.distance(Eigen::Vector3d(0, 0, 4)), 2.0);
}

TEST(CollisionMap, IsFreeWithOneMetreRadius) {
  TsdfMap map(mapConfig());
  fillKnownFree(&map);
  setVoxel(&map, Eigen::Vector3i(16, 16, 16), VoxelState::kOccupied);  // covers [0, 0.25] x [0, 0.25] x [4, 4.25]
  const CollisionMap coll(map, collisionConfig());
  EXPECT_TRUE(coll.isFree(Eigen::Vector3d(1.3, 0.1, 4.1), 1.0));
  EXPECT_FALSE(coll.isFree(Eigen::Vector3d(1.2, 0.1, 4.1), 1.0));
  EXPECT_FALSE(coll.isFree(Eigen::Vector3d(-0.9, 0.1, 4.1), 1.0));
  EXPECT_TRUE(coll.isFree(Eigen::Vector3d(0.9, 0.9, 4.9), 1.0));   // sqrt(3) * 0.65 = 1.13 m from the corner
  EXPECT_FALSE(coll.isFree(Eigen::Vector3d(0.7, 0.7, 4.7), 1.0));  // 0.78 m
  EXPECT_FALSE(coll.isFree(Eigen::Vector3d(3, 3, 7), 2.0));        // the cap cannot certify 2 m
}

TEST(CollisionMap, IncrementalWallMatchesScratch) {
  TsdfMap map(mapConfig());
  fillKnownFree(&map);
  const CollisionConfig config = collisionConfig();
  CollisionMap coll(map, config);
  // A wall x = 12 (block x = 1), y, z in [4, 20): blocks y, z in {0, 1, 2}.
  for (int z = 4; z < 20; ++z)
    for (int y = 4; y < 20; ++y) setVoxel(&map, Eigen::Vector3i(12, y, z), VoxelState::kOccupied);
  coll.update(map);
  EXPECT_EQ(coll.lastBlocksVisited(), 9u);
  EXPECT_EQ(coll.lastCellsEvaluated(), 9u * kBlockVoxels);
  EXPECT_EQ(coll.lastCellsChanged(), 256u);
  EXPECT_NEAR(coll.distance(Eigen::Vector3d(0.75, -1.0, 3.0)), 1.5, 1e-12);  // wall spans x in [-1, -0.75]
  expectSameAsScratch(coll, map, config);
  for (int z = 4; z < 20; ++z)
    for (int y = 4; y < 20; ++y) setVoxel(&map, Eigen::Vector3i(12, y, z), VoxelState::kFree);
  coll.update(map);
  EXPECT_EQ(coll.lastCellsChanged(), 256u);
  EXPECT_EQ(coll.distance(Eigen::Vector3d(0.75, -1.0, 3.0)), 2.0);
  expectSameAsScratch(coll, map, config);
}

TEST(CollisionMap, OnlyChangedBlocksAreVisited) {
  TsdfMap map(mapConfig());
  fillKnownFree(&map);
  CollisionMap coll(map, collisionConfig());
  coll.update(map);
  EXPECT_EQ(coll.lastBlocksVisited(), 0u);
  EXPECT_EQ(coll.lastCellsChanged(), 0u);
  setVoxel(&map, Eigen::Vector3i(20, 3, 9), VoxelState::kOccupied);
  coll.update(map);
  EXPECT_EQ(coll.lastBlocksVisited(), 1u);
  EXPECT_EQ(coll.lastCellsEvaluated(), static_cast<size_t>(kBlockVoxels));
  EXPECT_EQ(coll.lastCellsChanged(), 1u);
  EXPECT_TRUE(coll.isObstacleCell(Eigen::Vector3i(20, 3, 9)));
  setVoxel(&map, Eigen::Vector3i(20, 4, 9), VoxelState::kFree);  // stamped, state unchanged
  coll.update(map);
  EXPECT_EQ(coll.lastBlocksVisited(), 1u);
  EXPECT_EQ(coll.lastCellsChanged(), 0u);
}

TEST(CollisionMap, RandomEditsMatchScratch) {
  for (const double voxel : {0.25, 0.1}) {  // cells of 2 voxels, and of 3 that straddle blocks
    TsdfMap map(mapConfig(voxel));
    CollisionConfig config;
    config.bounds_are_obstacle = false;
    CollisionMap coll(map, config);
    std::mt19937 rng(5);
    const Eigen::Vector3i g = map.gridVoxels();
    std::uniform_int_distribution<int> state(0, 2), len(1, 12);
    for (int round = 0; round < 6; ++round) {
      for (int box = 0; box < 8; ++box) {  // boxes of one random state
        const Eigen::Vector3i lo(rng() % g.x(), rng() % g.y(), rng() % g.z());
        const Eigen::Vector3i hi = (lo + Eigen::Vector3i(len(rng), len(rng), len(rng))).cwiseMin(g);
        const VoxelState s = static_cast<VoxelState>(round == 0 ? 2 : state(rng));
        for (int z = lo.z(); z < hi.z(); ++z)
          for (int y = lo.y(); y < hi.y(); ++y)
            for (int x = lo.x(); x < hi.x(); ++x) setVoxel(&map, Eigen::Vector3i(x, y, z), s);
      }
      coll.update(map);
      SCOPED_TRACE("voxel " + std::to_string(voxel) + " round " + std::to_string(round));
      expectSameAsScratch(coll, map, config);
    }
  }
}

TEST(CollisionMap, ClearedMapRebuilds) {
  TsdfMap map(mapConfig());
  fillKnownFree(&map);
  CollisionMap coll(map, collisionConfig());
  EXPECT_EQ(coll.distance(Eigen::Vector3d(0, 0, 4)), 2.0);
  map.clear();
  coll.update(map);
  EXPECT_EQ(coll.distance(Eigen::Vector3d(0, 0, 4)), 0.0);
  EXPECT_EQ(coll.lastCellsChanged(), static_cast<size_t>(coll.gridCells().prod()));
}
