// coverClusters: the greedy cover of each cluster's ISEs by its viewpoints,
// preferred viewpoints first, the marginal threshold, and what it leaves of
// the frontier (clusters' gains, the dropped viewpoints' cluster -1).
#include <gtest/gtest.h>

#include <vector>

#include "surface_nbv/planning/cluster_cover.h"

using namespace surface_nbv;

namespace {

// Clusters of viewpoints given by their C_q (ISE indices), 1 m apart on x.
Frontier frontierOf(const std::vector<std::vector<std::vector<uint32_t>>>& clusters) {
  Frontier f;
  for (const auto& views : clusters) {
    Cluster c;
    for (const auto& visible : views) {
      Viewpoint v;
      v.position = Eigen::Vector3d(static_cast<double>(f.viewpoints.size()), 0.0, 2.0);
      v.visible = visible;
      v.cluster = static_cast<int32_t>(f.clusters.size());
      c.viewpoints.push_back(static_cast<uint32_t>(f.viewpoints.size()));
      f.viewpoints.push_back(v);
    }
    c.visible_ises = 10;
    c.gain = 0.5;
    f.clusters.push_back(c);
  }
  return f;
}

std::vector<uint32_t> kept(const Frontier& f, size_t cluster) { return f.clusters[cluster].viewpoints; }

}  // namespace

// Viewpoint 1 sees everything 0 and 2 see: it alone covers the cluster.
// The second cluster needs two of its three (3 and 5; 4 adds nothing then).
TEST(ClusterCover, KeepsAGreedyCoverOfEachCluster) {
  const Frontier f = frontierOf({{{1, 2}, {1, 2, 3, 4}, {3, 4}}, {{10, 11, 12}, {11, 12}, {13, 14}}});
  ClusterCoverStats stats;
  const Frontier c = coverClusters(f, {}, 1, &stats);
  EXPECT_EQ(kept(c, 0), (std::vector<uint32_t>{1}));
  EXPECT_EQ(kept(c, 1), (std::vector<uint32_t>{3, 5}));
  EXPECT_EQ(stats.kept, 3u);
  EXPECT_EQ(stats.dropped, 3u);
  for (uint32_t i : {0u, 2u, 4u}) EXPECT_EQ(c.viewpoints[i].cluster, -1) << i;
  for (uint32_t i : {1u}) EXPECT_EQ(c.viewpoints[i].cluster, 0) << i;
  for (uint32_t i : {3u, 5u}) EXPECT_EQ(c.viewpoints[i].cluster, 1) << i;
  // Gains and everything else as they were.
  ASSERT_EQ(c.clusters.size(), 2u);
  EXPECT_EQ(c.clusters[1].gain, 0.5);
  EXPECT_EQ(c.clusters[1].visible_ises, 10u);
  EXPECT_EQ(c.viewpoints.size(), f.viewpoints.size());
  EXPECT_EQ(c.viewpoints[4].visible, f.viewpoints[4].visible);
}

// Preferred viewpoints are kept while they add anything, the higher priority
// first; the greedy then fills in only what they leave.
TEST(ClusterCover, PrefersTheTourAndItsTarget) {
  const Frontier f = frontierOf({{{1, 2}, {1, 2, 3, 4}, {3, 4}, {2, 3}}});
  // 0 and 2 preferred: both kept, and together they see all, so 1 goes.
  std::vector<char> preferred{1, 0, 1, 0};
  EXPECT_EQ(kept(coverClusters(f, preferred, 1), 0), (std::vector<uint32_t>{0, 2}));
  // 3 the target (2), 0 and 2 in the tour (1): 3 first sees {2, 3}; 0 adds 1
  // and 2 adds 4, so all three stay.
  preferred = {1, 0, 1, 2};
  EXPECT_EQ(kept(coverClusters(f, preferred, 1), 0), (std::vector<uint32_t>{0, 2, 3}));
  // A preferred viewpoint that adds nothing is dropped: 1 (the target) sees all.
  preferred = {1, 2, 0, 0};
  EXPECT_EQ(kept(coverClusters(f, preferred, 1), 0), (std::vector<uint32_t>{1}));
  // A short `preferred` leaves the rest unpreferred.
  EXPECT_EQ(kept(coverClusters(f, {0, 0}, 1), 0), (std::vector<uint32_t>{1}));
}

// min_new: a viewpoint that would add fewer ISEs than that is not taken,
// but a cluster always keeps one.
TEST(ClusterCover, StopsBelowMinNewButKeepsOnePerCluster) {
  const Frontier f = frontierOf({{{1, 2, 3}, {3, 4}, {5}}, {{7, 8}}});
  EXPECT_EQ(kept(coverClusters(f, {}, 1), 0), (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(kept(coverClusters(f, {}, 2), 0), (std::vector<uint32_t>{0}));  // 1 adds {4}, 2 adds {5}
  EXPECT_EQ(kept(coverClusters(f, {}, 3), 1), (std::vector<uint32_t>{3}));  // the cluster's only one
  // Ties go to the lowest index.
  const Frontier tie = frontierOf({{{1, 2}, {3, 4}, {1, 2}}});
  EXPECT_EQ(kept(coverClusters(tie, {}, 1), 0), (std::vector<uint32_t>{0, 1}));
  // An empty frontier stays empty.
  EXPECT_TRUE(coverClusters(Frontier(), {}, 1).clusters.empty());
}
