#include "surface_nbv/planning/cluster_graph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "planning_test_worlds.h"
#include "surface_nbv/planning/path_planner.h"
#include "surface_nbv/surface/viewpoint_utility.h"

using namespace surface_nbv;

namespace {

double euclid(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm(); }

// Appends a cluster of the given viewpoint positions and gain.
void addCluster(Frontier& f, const std::vector<Eigen::Vector3d>& positions, double gain) {
  Cluster c;
  for (const Eigen::Vector3d& p : positions) {
    Viewpoint v;
    v.position = p;
    v.yaw = 0.1 * f.viewpoints.size();
    v.cluster = static_cast<int32_t>(f.clusters.size());
    c.viewpoints.push_back(static_cast<uint32_t>(f.viewpoints.size()));
    f.viewpoints.push_back(v);
  }
  c.gain = gain;
  f.clusters.push_back(c);
}

// Every cluster of `expected` exactly once, and every one of their viewpoints once.
void expectCovers(const Frontier& f, const TourPlan& plan, std::vector<int> expected) {
  std::vector<int> order = plan.clusters;
  std::sort(order.begin(), order.end());
  EXPECT_EQ(order, expected);
  std::vector<uint32_t> want;
  for (int c : expected) want.insert(want.end(), f.clusters[c].viewpoints.begin(), f.clusters[c].viewpoints.end());
  std::sort(want.begin(), want.end());
  std::vector<uint32_t> got = plan.viewpoints;
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, want);
  ASSERT_EQ(plan.configurations.size(), plan.viewpoints.size());
  for (size_t i = 0; i < got.size(); ++i) {
    const Viewpoint& v = f.viewpoints[plan.viewpoints[i]];
    EXPECT_EQ(plan.configurations[i], Eigen::Vector4d(v.position.x(), v.position.y(), v.position.z(), v.yaw));
  }
}

}  // namespace

TEST(ClusterGraph, HandComputedWeightsEq4Eq5) {
  Frontier f;
  addCluster(f, {{10, 0, 0}, {12, 0, 0}}, 0.5);              // A: viewpoints 0, 1
  addCluster(f, {{0, 10, 0}, {0, 13, 0}, {0, 14, 0}}, 0.25);  // B: viewpoints 2, 3, 4
  const ClusterGraph g(f, Eigen::Vector4d(0, 0, 0, 0.3), euclid);
  ASSERT_TRUE(g.status()) << g.status().message();
  ASSERT_EQ(g.nodeCount(), 3);
  const double ltc = 0.3, lic = 0.03, gmax = 0.5;

  const ClusterEdge& sa = g.edge(0, 1);  // UAV -> A: enter at 10, path 10 -> 12
  EXPECT_EQ(sa.k_viewpoint, -1);
  EXPECT_EQ(sa.l_viewpoint, 0u);
  EXPECT_EQ(sa.tau_lm, (std::vector<uint32_t>{0, 1}));
  EXPECT_NEAR(sa.d_kl, 10.0, 1e-9);
  EXPECT_NEAR(sa.d_lm, 2.0, 1e-9);
  EXPECT_NEAR(sa.utility, 0.5 * std::exp(-ltc * 10 - lic * 2), 1e-9);
  EXPECT_NEAR(sa.cost, ltc * 10 + lic * 2, 1e-9);

  const ClusterEdge& sb = g.edge(0, 2);  // UAV -> B: enter at y=10, path 10 -> 13 -> 14
  EXPECT_EQ(sb.tau_lm, (std::vector<uint32_t>{2, 3, 4}));
  EXPECT_NEAR(sb.d_lm, 4.0, 1e-9);
  EXPECT_NEAR(sb.utility, 0.25 * std::exp(-ltc * 10 - lic * 4), 1e-9);
  EXPECT_NEAR(sb.cost, ltc * 10 + lic * 4 - std::log(0.25) + std::log(gmax), 1e-9);

  // A's exit: entries 0 and 1 tie at 2 m, the lower position wins: exit = viewpoint 1 (12, 0, 0).
  const ClusterEdge& ab = g.edge(1, 2);
  EXPECT_EQ(ab.k_viewpoint, 1);
  EXPECT_EQ(ab.l_viewpoint, 2u);
  EXPECT_NEAR(ab.d_kl, std::sqrt(244.0), 1e-9);
  EXPECT_NEAR(ab.d_lm, 4.0, 1e-9);
  EXPECT_NEAR(ab.utility, 0.25 * std::exp(-ltc * std::sqrt(244.0) - lic * 4), 1e-9);
  // B's exit: entries y=10 and y=14 tie at 4 m, y=10 wins: exit = viewpoint 4 (0, 14, 0).
  const ClusterEdge& ba = g.edge(2, 1);
  EXPECT_EQ(ba.k_viewpoint, 4);
  EXPECT_EQ(ba.l_viewpoint, 0u);
  EXPECT_NEAR(ba.d_kl, std::sqrt(296.0), 1e-9);
  EXPECT_NEAR(ba.utility, 0.5 * std::exp(-ltc * std::sqrt(296.0) - lic * 2), 1e-9);
  EXPECT_TRUE(g.costs().validate()) << g.costs().validate().message();
  EXPECT_EQ(g.costs()(1, 2), ab.cost);

  const TourPlan plan = planTour(g);
  ASSERT_EQ(plan.status, TourPlanStatus::kOk) << plan.message;
  EXPECT_EQ(plan.clusters, (std::vector<int>{0, 1}));
  EXPECT_EQ(plan.viewpoints, (std::vector<uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_NEAR(plan.cost, sa.cost + ab.cost, 1e-9);
  EXPECT_NEAR(plan.utility, sa.utility + ab.utility, 1e-9);
  EXPECT_NEAR(plan.flight_length, 10 + 2 + std::sqrt(244.0) + 3 + 1, 1e-9);
  EXPECT_TRUE(plan.unreachable.empty());
}

// The two tour objectives on a line: A (gain 0.01) 1 m ahead of the UAV, B
// and C (gain 1) 3 and 4 m behind it. The product of the utilities ignores
// the gains (each cluster is entered once) and takes the shortest path,
// A first (6 m against 9 m); the sum (the paper's total utility) flies to
// B and C first: 0.407 + 0.741 + 0.002 = 1.150 against 1.049 for A first.
// Either way the plan is the best of all 6 orders by its own objective.
TEST(ClusterGraph, SumObjectiveMaximisesTheTotalUtilityProductTheShortestPath) {
  Frontier f;
  addCluster(f, {{1, 0, 0}}, 0.01);
  addCluster(f, {{-3, 0, 0}}, 1.0);
  addCluster(f, {{-4, 0, 0}}, 1.0);
  for (TourObjective objective : {TourObjective::kProduct, TourObjective::kSum}) {
    ClusterGraphConfig config;
    config.objective = objective;
    const ClusterGraph g(f, Eigen::Vector4d::Zero(), euclid, config);
    ASSERT_TRUE(g.status()) << g.status().message();
    const TourPlan plan = planTour(g);
    ASSERT_EQ(plan.status, TourPlanStatus::kOk) << plan.message;
    std::vector<int> order = {0, 1, 2};
    double best_sum = 0.0, best_product = 0.0;
    do {
      double sum = 0.0, product = 1.0;
      int from = 0;
      for (int c : order) {
        sum += g.edge(from, c + 1).utility;
        product *= g.edge(from, c + 1).utility;
        from = c + 1;
      }
      best_sum = std::max(best_sum, sum);
      best_product = std::max(best_product, product);
    } while (std::next_permutation(order.begin(), order.end()));
    double product = 1.0;
    int from = 0;
    for (int c : plan.clusters) product *= g.edge(from, c + 1).utility, from = c + 1;
    if (objective == TourObjective::kSum) {
      EXPECT_EQ(plan.clusters, (std::vector<int>{1, 2, 0}));
      EXPECT_NEAR(plan.utility, best_sum, 1e-12);
      for (int v = 1; v <= 3; ++v) {
        const ClusterEdge& e = g.edge(0, v);
        EXPECT_NEAR(e.cost, utilitySumCost(e.utility, 1.0), 1e-12);
        EXPECT_GE(e.cost, 0.0);
        EXPECT_LE(e.cost, kSumCostScale);
      }
    } else {
      EXPECT_EQ(plan.clusters, (std::vector<int>{0, 1, 2}));
      EXPECT_NEAR(product, best_product, 1e-15);
      EXPECT_LT(plan.utility, best_sum - 0.05);
    }
  }
  TourObjective parsed = TourObjective::kProduct;
  EXPECT_TRUE(parseTourObjective("sum", &parsed));
  EXPECT_EQ(parsed, TourObjective::kSum);
  EXPECT_STREQ(toString(parsed), "sum");
  EXPECT_TRUE(parseTourObjective("product", &parsed));
  EXPECT_EQ(parsed, TourObjective::kProduct);
  EXPECT_FALSE(parseTourObjective("Sum", &parsed));
  EXPECT_EQ(parsed, TourObjective::kProduct);
  EXPECT_DOUBLE_EQ(utilitySumCost(0.0, 0.5), kSumCostScale);
  EXPECT_DOUBLE_EQ(utilitySumCost(0.5, 0.5), 0.0);
}

TEST(ClusterGraph, ExactIntraPathMatchesBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i < kExactClusterSize; ++i) pts.emplace_back(u(rng), u(rng), u(rng));
    Frontier f;
    addCluster(f, pts, 1.0);
    const ClusterGraph g(f, Eigen::Vector4d(20, 20, 20, 0), euclid);
    const ClusterEdge& e = g.edge(0, 1);
    std::vector<int> rest;
    for (int i = 0; i < kExactClusterSize; ++i)
      if (uint32_t(i) != e.l_viewpoint) rest.push_back(i);
    double best = std::numeric_limits<double>::infinity();
    do {
      double len = euclid(pts[e.l_viewpoint], pts[rest[0]]);
      for (size_t i = 1; i < rest.size(); ++i) len += euclid(pts[rest[i - 1]], pts[rest[i]]);
      best = std::min(best, len);
    } while (std::next_permutation(rest.begin(), rest.end()));
    EXPECT_NEAR(e.d_lm, best, 1e-9);
    EXPECT_EQ(e.tau_lm.front(), e.l_viewpoint);
  }
}

TEST(ClusterGraph, LargeClusterUsesHeuristicAndFindsTheLine) {
  std::vector<Eigen::Vector3d> pts;
  for (int x : {5, 0, 11, 3, 8, 1, 10, 6, 2, 9, 4, 7}) pts.emplace_back(x, 0, 0);
  Frontier f;
  addCluster(f, pts, 1.0);
  const ClusterGraph g(f, Eigen::Vector4d(-5, 0, 0, 0), euclid);
  const ClusterEdge& e = g.edge(0, 1);
  EXPECT_NEAR(e.d_kl, 5.0, 1e-9);
  EXPECT_NEAR(e.d_lm, 11.0, 1e-9);
  ASSERT_EQ(e.tau_lm.size(), pts.size());
  for (size_t i = 0; i < pts.size(); ++i) EXPECT_EQ(f.viewpoints[e.tau_lm[i]].position.x(), double(i));
}

TEST(ClusterGraph, NoClusterIsNothingToDo) {
  Frontier f;
  const ClusterGraph g(f, Eigen::Vector4d::Zero(), euclid);
  ASSERT_TRUE(g.status());
  EXPECT_EQ(g.clusterCount(), 0);
  const TourPlan plan = planTour(g);
  EXPECT_EQ(plan.status, TourPlanStatus::kNothingToDo);
  EXPECT_STRNE(toString(plan.status), toString(TourPlanStatus::kOk));
  EXPECT_TRUE(plan.clusters.empty());
  EXPECT_TRUE(plan.viewpoints.empty());
  EXPECT_EQ(plan.utility, 0.0);
}

TEST(ClusterGraph, OneTwoThreeClustersVisitedOnceFromTheUav) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-30, 30);
  for (int n = 1; n <= 3; ++n) {
    Frontier f;
    for (int c = 0; c < n; ++c) {
      const Eigen::Vector3d centre(u(rng), u(rng), u(rng));
      addCluster(f, {centre, centre + Eigen::Vector3d(1, 0, 0), centre + Eigen::Vector3d(0, 2, 0)}, 0.1 * (c + 1));
    }
    const ClusterGraph g(f, Eigen::Vector4d(1, 2, 3, 0), euclid);
    const TourPlan plan = planTour(g);
    ASSERT_EQ(plan.status, TourPlanStatus::kOk) << n;
    std::vector<int> all(n);
    for (int c = 0; c < n; ++c) all[c] = c;
    expectCovers(f, plan, all);
    EXPECT_EQ(plan.viewpoints.front(), g.edge(0, plan.clusters.front() + 1).l_viewpoint);
    EXPECT_GT(plan.utility, 0.0);
    EXPECT_GE(plan.cost, 0.0);
  }
}

TEST(ClusterGraph, UnreachableClusterIsExcludedAndReported) {
  Frontier f;
  addCluster(f, {{5, 0, 0}, {6, 0, 0}}, 0.3);
  addCluster(f, {{0, 0, 100}, {1, 0, 100}}, 0.9);  // above the ceiling: no path
  addCluster(f, {{0, 5, 0}}, 0.2);
  const DistanceFn below = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a.z() > 50 || b.z() > 50 ? std::numeric_limits<double>::infinity() : (a - b).norm();
  };
  const ClusterGraph g(f, Eigen::Vector4d::Zero(), below);
  ASSERT_TRUE(g.status());
  for (int u : {0, 1, 3}) {
    EXPECT_FALSE(g.edge(u, 2).reachable);
    EXPECT_EQ(g.edge(u, 2).cost, CostMatrix::kUnreachable);
    EXPECT_EQ(g.edge(u, 2).utility, 0.0);
  }
  EXPECT_TRUE(g.costs().validate());
  const TourPlan plan = planTour(g);
  ASSERT_EQ(plan.status, TourPlanStatus::kOk);
  EXPECT_EQ(plan.unreachable, (std::vector<int>{1}));
  expectCovers(f, plan, {0, 2});
  EXPECT_TRUE(std::isfinite(plan.flight_length));

  Frontier only;
  addCluster(only, {{0, 0, 100}}, 0.5);
  const TourPlan none = planTour(ClusterGraph(only, Eigen::Vector4d::Zero(), below));
  EXPECT_EQ(none.status, TourPlanStatus::kNoReachableCluster);
  EXPECT_EQ(none.unreachable, (std::vector<int>{0}));
  EXPECT_TRUE(none.viewpoints.empty());
}

TEST(ClusterGraph, DuplicateViewpointsAreAllVisited) {
  Frontier f;
  addCluster(f, {{3, 0, 0}, {3, 0, 0}, {4, 0, 0}}, 0.4);
  addCluster(f, {{4, 0, 0}, {4, 0, 0}}, 0.4);
  const ClusterGraph g(f, Eigen::Vector4d::Zero(), euclid);
  EXPECT_TRUE(g.costs().validate());
  EXPECT_NEAR(g.edge(0, 1).d_lm, 1.0, 1e-12);
  EXPECT_NEAR(g.edge(1, 2).d_kl, 0.0, 1e-12);
  const TourPlan plan = planTour(g);
  ASSERT_EQ(plan.status, TourPlanStatus::kOk);
  expectCovers(f, plan, {0, 1});
  EXPECT_NEAR(plan.flight_length, 4.0, 1e-12);
}

TEST(ClusterGraph, ZeroGainClusterIsSkipped) {
  Frontier f;
  addCluster(f, {{1, 0, 0}}, 0.0);
  addCluster(f, {{2, 0, 0}}, 0.5);
  const TourPlan plan = planTour(ClusterGraph(f, Eigen::Vector4d::Zero(), euclid));
  ASSERT_EQ(plan.status, TourPlanStatus::kOk);
  EXPECT_EQ(plan.no_gain, (std::vector<int>{0}));
  EXPECT_EQ(plan.clusters, (std::vector<int>{1}));
}

TEST(ClusterGraph, BadInputIsRefused) {
  Frontier f;
  addCluster(f, {{1, 0, 0}}, 0.5);
  ClusterGraphConfig bad;
  bad.lambda_tc = -1.0;
  EXPECT_FALSE(bad.validate());
  const ClusterGraph g(f, Eigen::Vector4d::Zero(), euclid, bad);
  EXPECT_FALSE(g.status());
  EXPECT_EQ(g.nodeCount(), 0);
  EXPECT_EQ(planTour(g).status, TourPlanStatus::kInvalidGraph);
  EXPECT_FALSE(ClusterGraph(f, Eigen::Vector4d::Zero(), DistanceFn()).status());
  f.clusters[0].viewpoints.push_back(99);
  EXPECT_FALSE(ClusterGraph(f, Eigen::Vector4d::Zero(), euclid).status());
}

// Entry q_l is the viewpoint closest by path length: behind the wall of
// WallWorld (gap at y >= 1 m), the viewpoint nearer in straight line is the
// farther one to fly to.
TEST(ClusterGraph, EntryClosestByPathLengthWithThePlannerOracle) {
  const WallWorld world(true);
  PathPlannerConfig c;
  c.iteration_budget = 3000;
  c.seed = 7;
  PathPlanner planner(c);
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  const Eigen::Vector4d uav(-4.0, -3.0, 2.5, 0.0);
  const Eigen::Vector3d behind(2.0, -3.0, 2.5), through(3.5, 3.0, 2.5);
  ASSERT_TRUE(hasPath(planner.plan(uav, Eigen::Vector4d(behind.x(), behind.y(), behind.z(), 0.0)).status));
  ASSERT_TRUE(hasPath(planner.plan(uav, Eigen::Vector4d(through.x(), through.y(), through.z(), 0.0)).status));
  Frontier f;
  addCluster(f, {behind, through}, 1.0);
  const ClusterGraph straight(f, uav, euclid);
  ASSERT_TRUE(straight.status());
  EXPECT_EQ(straight.edge(0, 1).l_viewpoint, 0u);
  const ClusterGraph by_path(f, uav, planner.distanceOracle());
  ASSERT_TRUE(by_path.status());
  const ClusterEdge& e = by_path.edge(0, 1);
  EXPECT_EQ(e.l_viewpoint, 1u);
  EXPECT_TRUE(e.reachable);
  EXPECT_GT(e.d_kl, (through - uav.head<3>()).norm());
}
