#include "surface_nbv/surface/viewpoint_clusterer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "surface_test_maps.h"

using namespace surface_nbv;
using namespace surface_nbv::test;

namespace {

Viewpoint at(double x, double y, double z, std::vector<uint32_t> visible = {}) {
  Viewpoint v;
  v.position = Eigen::Vector3d(x, y, z);
  v.visible = std::move(visible);
  return v;
}

struct FreeWorld : FreeMap {
  std::vector<Cluster> cluster(std::vector<Viewpoint>* viewpoints, size_t num_ises = 0,
                               std::vector<std::pair<int, int>>* links = nullptr, int threads = 1) {
    SurfaceConfig config = testSurfaceConfig();
    config.threads = threads;
    return ViewpointClusterer(config).cluster(*collision, num_ises, viewpoints, links);
  }
};

}  // namespace

TEST(ViewpointClusterer, ViewpointsWithinDnuChainIntoOneCluster) {
  FreeWorld world;
  std::vector<Viewpoint> q = {at(2, 2, 3), at(3.5, 2, 3), at(5, 2, 3), at(6.5, 2, 3)};
  std::vector<std::pair<int, int>> links;
  const auto clusters = world.cluster(&q, 0, &links);
  ASSERT_EQ(clusters.size(), 1u);
  EXPECT_EQ(clusters[0].viewpoints, (std::vector<uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(links, (std::vector<std::pair<int, int>>{{0, 1}, {1, 2}, {2, 3}}));
  for (const Viewpoint& v : q) EXPECT_EQ(v.cluster, 0);
}

TEST(ViewpointClusterer, IsolatedViewpointGrowsDnuUpToDnuMax) {
  FreeWorld world;
  {  // 3 m apart: d_nu grows 2 -> 2.5 -> 3 -> 3.5 and they join.
    std::vector<Viewpoint> q = {at(2, 6, 3), at(5, 6, 3)};
    EXPECT_EQ(world.cluster(&q).size(), 1u);
  }
  {  // 6 m apart: beyond d_nu_max = 5, two clusters.
    std::vector<Viewpoint> q = {at(2, 6, 3), at(8, 6, 3)};
    EXPECT_EQ(world.cluster(&q).size(), 2u);
  }
  {  // Two pairs 1.5 m apart inside, 4 m between the pairs: each viewpoint
     // has a neighbour within d_nu, so none grows, two clusters.
    std::vector<Viewpoint> q = {at(2, 6, 3), at(3.5, 6, 3), at(7.5, 6, 3), at(9, 6, 3)};
    const auto clusters = world.cluster(&q);
    ASSERT_EQ(clusters.size(), 2u);
    EXPECT_EQ(clusters[1].viewpoints, (std::vector<uint32_t>{2, 3}));
  }
  {  // A lone viewpoint links only to those within its first grown radius (3.5 m).
    std::vector<Viewpoint> q = {at(1.5, 6, 3), at(3, 6, 3), at(6, 6, 3), at(9.5, 6, 3), at(10.5, 6, 3)};
    std::vector<std::pair<int, int>> links;
    const auto clusters = world.cluster(&q, 0, &links);
    EXPECT_EQ(links, (std::vector<std::pair<int, int>>{{0, 1}, {1, 2}, {3, 4}}));
    EXPECT_EQ(clusters.size(), 2u);
  }
}

TEST(ViewpointClusterer, AWallBetweenViewpointsSeparatesThem) {
  FreeWorld world;
  std::vector<Viewpoint> q = {at(2, 6, 3), at(5, 6, 3)};
  fillBox(&world.map, Eigen::Vector3i(14, 0, 0), Eigen::Vector3i(15, 48, 24), VoxelState::kOccupied);  // x in [3.5, 3.75)
  world.collision = collisionFor(world.map);
  EXPECT_EQ(world.cluster(&q).size(), 2u);
  const ViewpointClusterer clusterer(testSurfaceConfig());
  EXPECT_FALSE(clusterer.segmentFree(*world.collision, q[0].position, q[1].position));
  EXPECT_TRUE(clusterer.segmentFree(*world.collision, q[0].position, Eigen::Vector3d(2, 10, 3)));
}

TEST(ViewpointClusterer, SegmentCheckAgreesWithDenseSampling) {
  FreeWorld world;
  std::mt19937 rng(31);
  std::uniform_int_distribution<int> cell(0, 47), height(0, 23);
  for (int i = 0; i < 60; ++i) setState(&world.map, Eigen::Vector3i(cell(rng), cell(rng), height(rng)), VoxelState::kOccupied);
  world.collision = collisionFor(world.map);
  const ViewpointClusterer clusterer(testSurfaceConfig());
  std::uniform_real_distribution<double> u(1.2, 10.8), h(1.2, 4.8);
  int free_count = 0, compared = 0;
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector3d a(u(rng), u(rng), h(rng)), b(u(rng), u(rng), h(rng));
    double clearance = 1e9;
    for (int k = 0; k <= 2000; ++k) clearance = std::min(clearance, world.collision->distance(a + (b - a) * (k / 2000.0)));
    const bool fast = clusterer.segmentFree(*world.collision, a, b);
    free_count += fast ? 1 : 0;
    // Between its samples the check may miss a dip of a few millimetres.
    if (std::abs(clearance - 1.0) < 0.01) continue;
    ++compared;
    EXPECT_EQ(fast, clearance > 1.0) << a.transpose() << " -> " << b.transpose() << ": " << clearance;
  }
  EXPECT_GT(compared, 380);
  EXPECT_GT(free_count, 20);
  EXPECT_LT(free_count, 380);
}

TEST(ViewpointClusterer, GainIsTheUnionOfVisibleSetsOverAllIses) {
  FreeWorld world;
  std::vector<Viewpoint> q = {at(2, 2, 3, {0, 1, 2}), at(3, 2, 3, {2, 3}), at(10, 10, 3, {5})};
  const auto clusters = world.cluster(&q, 10);
  ASSERT_EQ(clusters.size(), 2u);
  EXPECT_EQ(clusters[0].visible_ises, 4u);
  EXPECT_DOUBLE_EQ(clusters[0].gain, 0.4);
  EXPECT_EQ(clusters[1].visible_ises, 1u);
  EXPECT_DOUBLE_EQ(clusters[1].gain, 0.1);
  EXPECT_DOUBLE_EQ(world.cluster(&q, 0)[0].gain, 0.0);
}

TEST(ViewpointClusterer, SameClustersForAnyThreadCount) {
  FreeWorld world;
  std::mt19937 rng(37);
  std::uniform_int_distribution<int> cell(0, 47), height(0, 23);
  for (int i = 0; i < 80; ++i) setState(&world.map, Eigen::Vector3i(cell(rng), cell(rng), height(rng)), VoxelState::kOccupied);
  world.collision = collisionFor(world.map);
  std::uniform_real_distribution<double> u(1.2, 10.8), h(1.2, 4.8);
  std::vector<Viewpoint> q;
  for (int i = 0; i < 150; ++i) q.push_back(at(u(rng), u(rng), h(rng)));
  std::vector<Viewpoint> a = q, b = q;
  std::vector<std::pair<int, int>> links_a, links_b;
  const auto ca = world.cluster(&a, 0, &links_a, 1), cb = world.cluster(&b, 0, &links_b, 2);
  EXPECT_EQ(links_a, links_b);
  ASSERT_EQ(ca.size(), cb.size());
  for (size_t i = 0; i < ca.size(); ++i) EXPECT_EQ(ca[i].viewpoints, cb[i].viewpoints);
  EXPECT_GT(links_a.size(), 100u);
}
