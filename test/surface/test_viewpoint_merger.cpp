#include "surface_nbv/surface/viewpoint_merger.h"

#include <gtest/gtest.h>

#include <cmath>

#include "surface_test_maps.h"

using namespace surface_nbv;
using namespace surface_nbv::test;

namespace {

Viewpoint pose(double x, double y, double z, double yaw_deg, uint32_t source) {
  Viewpoint v;
  v.position = Eigen::Vector3d(x, y, z);
  v.yaw = yaw_deg * M_PI / 180.0;
  v.view_direction = Eigen::Vector3d(std::cos(v.yaw), std::sin(v.yaw), 0.0);
  v.sources = {source};
  return v;
}

struct FreeWorld : FreeMap {
  std::vector<Viewpoint> merge(const std::vector<Viewpoint>& poses, std::vector<int>* group_of = nullptr) {
    const ViewpointMerger merger(testSurfaceConfig());
    return merger.merge(poses, *collision, map.config().bounds, group_of);
  }
};

}  // namespace

TEST(ViewpointMerger, PosesWithinEpsilonBecomeOneAtTheirMean) {
  FreeWorld world;
  std::vector<int> group_of;
  const auto merged = world.merge({pose(5, 5, 3, 0, 4), pose(5.5, 5, 3, 90, 1), pose(5, 5.6, 3, 180, 7)}, &group_of);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_NEAR((merged[0].position - Eigen::Vector3d(5.5 / 3 + 10.0 / 3, 5.6 / 3 + 10.0 / 3, 3)).norm(), 0.0, 1e-12);
  EXPECT_EQ(merged[0].sources, (std::vector<uint32_t>{1, 4, 7}));
  EXPECT_EQ(group_of, (std::vector<int>{0, 0, 0}));
  // Orientation: the mean of the three directions (0, 90, 180 degrees) looks along +y.
  EXPECT_NEAR(merged[0].yaw, M_PI / 2, 1e-12);
}

TEST(ViewpointMerger, MeanOrientationOfTwoPoses) {
  FreeWorld world;
  const auto merged = world.merge({pose(5, 5, 3, 0, 0), pose(5.3, 5, 3, 90, 1)});
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_NEAR(merged[0].yaw, M_PI / 4, 1e-12);
  EXPECT_NEAR(merged[0].position.x(), 5.15, 1e-12);
}

TEST(ViewpointMerger, ParallelPosesMergeFartherThanEpsilon) {
  FreeWorld world;
  // 2 m apart (> epsilon 1.2, < parallel_distance 2.4).
  EXPECT_EQ(world.merge({pose(4, 5, 3, 0, 0), pose(4, 7, 3, 5, 1)}).size(), 1u);   // 5 degrees apart
  EXPECT_EQ(world.merge({pose(4, 5, 3, 0, 0), pose(4, 7, 3, 20, 1)}).size(), 2u);  // 20 degrees apart
  EXPECT_EQ(world.merge({pose(4, 5, 3, 0, 0), pose(4, 7, 3, 180, 1)}).size(), 2u); // opposite
  // 3 m apart: beyond parallel_distance, even when parallel.
  EXPECT_EQ(world.merge({pose(4, 5, 3, 0, 0), pose(4, 8, 3, 0, 1)}).size(), 2u);
}

TEST(ViewpointMerger, GroupsDoNotDriftAlongAChain) {
  FreeWorld world;
  // Poses 1 m apart along x, each within epsilon of the previous one, and
  // poses 2 m apart look opposite ways: a group only takes poses near its
  // seed, where chaining would make one group of all.
  std::vector<Viewpoint> chain;
  for (int i = 0; i < 8; ++i) chain.push_back(pose(2 + i, 6, 3, (i / 2) % 2 ? 90 : -90, i));
  std::vector<int> group_of;
  const auto merged = world.merge(chain, &group_of);
  EXPECT_EQ(merged.size(), 4u);
  EXPECT_EQ(group_of, (std::vector<int>{0, 0, 1, 1, 2, 2, 3, 3}));
}

TEST(ViewpointMerger, MeanPoseInCollisionKeepsTheSeedPose) {
  FreeWorld world;
  setState(&world.map, Eigen::Vector3d(5.15 / kVoxel, 5 / kVoxel, 3 / kVoxel).cast<int>(), VoxelState::kOccupied);
  world.collision = collisionFor(world.map);
  const auto merged = world.merge({pose(5, 5, 3, 0, 0), pose(5.3, 5, 3, 90, 1)});
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_EQ(merged[0].position, Eigen::Vector3d(5, 5, 3));
  EXPECT_EQ(merged[0].yaw, 0.0);
  EXPECT_EQ(merged[0].sources, (std::vector<uint32_t>{0, 1}));
}

TEST(ViewpointMerger, CountsOnAGrid) {
  FreeWorld world;
  // A 5 x 5 grid of poses 0.5 m apart, all looking +x: seeds every 1.5 m at most.
  std::vector<Viewpoint> poses;
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 5; ++i) poses.push_back(pose(3 + 0.5 * i, 3 + 0.5 * j, 3, 0, poses.size()));
  const auto merged = world.merge(poses);
  // Parallel poses closer than 2.4 m merge: the seed (3, 3) takes all but
  // (5, 4.5), (4.5, 5) and (5, 5), which form a second group.
  ASSERT_EQ(merged.size(), 2u);
  EXPECT_EQ(merged[0].sources.size(), 22u);
  EXPECT_EQ(merged[1].sources, (std::vector<uint32_t>{19, 23, 24}));
}
