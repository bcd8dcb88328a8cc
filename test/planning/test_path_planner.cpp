#include "surface_nbv/planning/path_planner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>
#include <vector>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/tsdf_map.h"
#include "planning_test_worlds.h"

using namespace surface_nbv;

namespace {

// The seed and roadmap samples of every plan here, and at most 10 s each.
constexpr unsigned int kSeed = 7;
constexpr int kIterations = 3000;
constexpr double kTimeBudget = 10.0;

const Eigen::Vector4d kStart(-4.0, -3.0, 2.5, 0.0);
const Eigen::Vector4d kGoal(4.0, -3.0, 2.5, 1.5);

void expectCollisionFree(const CollisionMap& map, const PathResult& r, double radius) {
  ASSERT_GE(r.path.size(), 2u);
  double length = 0.0;
  for (size_t k = 0; k + 1 < r.path.size(); ++k) {
    const Eigen::Vector3d a = r.path[k].head<3>(), b = r.path[k + 1].head<3>();
    const double d = (b - a).norm();
    length += d;
    const int steps = std::max(1, static_cast<int>(std::ceil(d / 0.1)));
    for (int i = 0; i <= steps; ++i) {
      const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(i) / steps);
      EXPECT_TRUE(map.isFree(p, radius)) << "segment " << k << " at " << p.transpose();
    }
  }
  EXPECT_NEAR(length, r.length, 1e-9);
}

}  // namespace

TEST(PathPlannerConfig, ValidateNamesTheKey) {
  EXPECT_TRUE(PathPlannerConfig().validate());
  PathPlannerConfig c;
  c.collision_radius = 0.0;
  EXPECT_EQ(c.validate().message(), "collision_radius expected > 0");
  c = PathPlannerConfig();
  c.iteration_budget = -1;
  EXPECT_EQ(c.validate().message(), "iteration_budget expected >= 0");
  c = PathPlannerConfig();
  c.time_budget = -1.0;
  EXPECT_FALSE(c.validate());
}

class GapTest : public ::testing::TestWithParam<std::tuple<unsigned int, bool>> {};

TEST_P(GapTest, PathGoesThroughTheGapAndIsCollisionFree) {
  const WallWorld world(true);
  PathPlannerConfig c = seededPlannerConfig(kSeed, kIterations, kTimeBudget);
  c.seed = std::get<0>(GetParam());
  c.stop_at_first_solution = std::get<1>(GetParam());
  PathPlanner planner(c);
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  const PathResult r = planner.plan(kStart, kGoal);
  ASSERT_EQ(r.status, PathStatus::kExactSolution) << toString(r.status);
  expectCollisionFree(world.collision(), r, 1.0);
  EXPECT_TRUE(r.path.front().isApprox(kStart));
  EXPECT_TRUE(r.path.back().head<3>().isApprox(kGoal.head<3>()));
  EXPECT_NEAR(r.path.back()[3], kGoal[3], 1e-9);
  // Yaw is monotone from start to goal here (turn of +1.5 rad).
  for (size_t k = 1; k < r.path.size(); ++k) EXPECT_GE(r.path[k][3], r.path[k - 1][3]);
  bool crossed = false;
  for (size_t k = 0; k + 1 < r.path.size(); ++k) {
    const Eigen::Vector3d a = r.path[k].head<3>(), b = r.path[k + 1].head<3>();
    if ((a.x() < 0.0) != (b.x() < 0.0)) {
      const double t = -a.x() / (b.x() - a.x());
      EXPECT_GT((a + t * (b - a)).y(), 1.0);
      crossed = true;
    }
  }
  EXPECT_TRUE(crossed);
  // Around the wall: longer than the straight line, but not absurdly.
  EXPECT_GT(r.length, 8.0);
  EXPECT_LT(r.length, 25.0);
  std::printf("query: %.4f s, %zu waypoints, %.2f m, roadmap %zu vertices\n", r.seconds, r.path.size(), r.length,
              planner.roadmapVertices());
}

INSTANTIATE_TEST_SUITE_P(Seeds, GapTest,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u), ::testing::Bool()));

TEST(PathPlanner, StartOrGoalInCollisionHaveTheirOwnStatus) {
  const WallWorld world(true);
  PathPlanner planner(seededPlannerConfig(kSeed, kIterations, kTimeBudget));
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  PathResult r = planner.plan(Eigen::Vector4d(0.0, -3.0, 2.5, 0.0), kGoal);
  EXPECT_EQ(r.status, PathStatus::kInvalidStart);
  EXPECT_TRUE(r.path.empty());
  r = planner.plan(Eigen::Vector4d(-0.7, -3.0, 2.5, 0.0), kGoal);  // 0.45 m from the wall: within 1 m
  EXPECT_EQ(r.status, PathStatus::kInvalidStart);
  r = planner.plan(kStart, Eigen::Vector4d(0.0, -3.0, 2.5, 0.0));
  EXPECT_EQ(r.status, PathStatus::kInvalidGoal);
  EXPECT_TRUE(r.path.empty());
  r = planner.plan(Eigen::Vector4d(-4.0, -3.0, 20.0, 0.0), kGoal);  // out of bounds
  EXPECT_EQ(r.status, PathStatus::kInvalidStart);
  r = planner.plan(Eigen::Vector4d(NAN, 0.0, 2.0, 0.0), kGoal);
  EXPECT_EQ(r.status, PathStatus::kInvalidInput);
}

// clearance(): what every accepted state keeps from obstacles, the radius
// plus half the motion-check step; the explorer's reachability fill uses it.
TEST(PathPlanner, ClearanceIsTheRadiusPlusHalfTheMotionCheckStep) {
  const WallWorld world(true);
  PathPlannerConfig config = seededPlannerConfig(kSeed, kIterations, kTimeBudget);
  config.validity_resolution = 0.2;
  PathPlanner planner(config);
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  EXPECT_NEAR(planner.clearance(), config.collision_radius + 0.1, 1e-12);
  // Goals beside the wall: refused while nearer than clearance(), accepted beyond it.
  int refused_beyond_radius = 0, accepted = 0;
  for (double x = -3.0; x < -0.3; x += 0.01) {
    const Eigen::Vector4d goal(x, -3.0, 2.5, 0.0);
    const double d = world.collision().distance(goal.head<3>());
    const PathStatus status = planner.plan(kStart, goal).status;
    if (d >= config.collision_radius && d < planner.clearance() - 1e-6) {
      EXPECT_EQ(status, PathStatus::kInvalidGoal) << "x " << x << " distance " << d;
      ++refused_beyond_radius;
    } else if (d > planner.clearance() + 1e-6 && status != PathStatus::kInvalidGoal) {
      ++accepted;
    }
  }
  EXPECT_GT(refused_beyond_radius, 0) << "no goal between the radius and the clearance";
  EXPECT_GT(accepted, 0);
  PathPlannerConfig fine = config;
  fine.validity_resolution = 0.0;  // half a collision cell
  PathPlanner default_step(fine);
  ASSERT_TRUE(default_step.setMap(&world.collision(), world.bounds()));
  EXPECT_NEAR(default_step.clearance(), fine.collision_radius + 0.25 * world.collision().cellSize(), 1e-12);
}

TEST(PathPlanner, NoMapIsInvalidInput) {
  PathPlanner planner;
  EXPECT_EQ(planner.plan(kStart, kGoal).status, PathStatus::kInvalidInput);
  EXPECT_FALSE(planner.setMap(nullptr, AlignedBox(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones())));
  const WallWorld world(true);
  EXPECT_FALSE(planner.setMap(&world.collision(), AlignedBox()));
}

TEST(PathPlanner, ClosedWallIsNotASuccess) {
  const WallWorld world(false);
  PathPlannerConfig c = seededPlannerConfig(kSeed, kIterations, kTimeBudget);
  c.iteration_budget = 1500;
  PathPlanner planner(c);
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  const PathResult r = planner.plan(kStart, kGoal);
  EXPECT_EQ(r.status, PathStatus::kNoSolution) << toString(r.status);
  EXPECT_TRUE(r.path.empty());
  EXPECT_TRUE(std::isinf(planner.pathLength(kStart.head<3>(), kGoal.head<3>())));
}

TEST(PathPlanner, ZeroTimeBudgetTimesOut) {
  const WallWorld world(true);
  PathPlannerConfig c;
  c.time_budget = 0.0;
  PathPlanner planner(c);
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  const PathResult r = planner.plan(kStart, kGoal);
  EXPECT_EQ(r.status, PathStatus::kTimeout);
  EXPECT_TRUE(r.path.empty());
  EXPECT_LT(r.seconds, 0.5);
}

// A caller's cap ends a call long before the config's budget would, over
// the roadmap and the lattice fallback together; a cap of 0 or NaN times
// out at once, and a generous one changes nothing.
TEST(PathPlanner, CallerCapBoundsACallBelowTheConfigBudget) {
  const WallWorld closed(false);
  PathPlannerConfig c = seededPlannerConfig(kSeed, kIterations, kTimeBudget);
  c.iteration_budget = 0;  // time only
  c.time_budget = 20.0;
  c.lattice_step = 0.25;
  c.lattice_max_nodes = 50000000;
  PathPlanner planner(c);
  ASSERT_TRUE(planner.setMap(&closed.collision(), closed.bounds()));
  const PathResult capped = planner.plan(kStart, kGoal, 0.3);
  EXPECT_EQ(capped.status, PathStatus::kTimeout) << toString(capped.status);
  EXPECT_TRUE(capped.path.empty());
  EXPECT_LT(capped.seconds, 5.0) << "the config alone allows 40 s";
  for (double cap : {0.0, -1.0, std::nan("")}) {
    const PathResult r = planner.plan(kStart, kGoal, cap);
    EXPECT_EQ(r.status, PathStatus::kTimeout) << cap;
    EXPECT_LT(r.seconds, 0.5) << cap;
  }
  const WallWorld open(true);
  PathPlannerConfig o = seededPlannerConfig(kSeed, kIterations, kTimeBudget);
  PathPlanner a(o), b(o);
  ASSERT_TRUE(a.setMap(&open.collision(), open.bounds()));
  ASSERT_TRUE(b.setMap(&open.collision(), open.bounds()));
  const PathResult uncapped = a.plan(kStart, kGoal), generous = b.plan(kStart, kGoal, 100.0);
  ASSERT_TRUE(hasPath(uncapped.status));
  ASSERT_EQ(uncapped.path.size(), generous.path.size());
  for (size_t i = 0; i < uncapped.path.size(); ++i) EXPECT_TRUE(uncapped.path[i].isApprox(generous.path[i]));
}

TEST(PathPlanner, TinyBudgetsGiveAConsistentAnswer) {
  const WallWorld world(true);
  for (int budget : {1, 2, 5, 20}) {
    PathPlannerConfig c = seededPlannerConfig(kSeed, kIterations, kTimeBudget);
    c.iteration_budget = budget;
    PathPlanner planner(c);
    ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
    const PathResult r = planner.plan(kStart, kGoal);
    EXPECT_EQ(hasPath(r.status), !r.path.empty()) << budget;
    if (hasPath(r.status)) expectCollisionFree(world.collision(), r, 1.0);
  }
  PathPlannerConfig c;
  c.time_budget = 1e-4;
  PathPlanner planner(c);
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  const PathResult r = planner.plan(kStart, kGoal);
  EXPECT_EQ(hasPath(r.status), !r.path.empty());
}

TEST(PathPlanner, RepeatedClearAndPlanRepeatExactly) {
  const WallWorld world(true);
  PathPlanner planner(seededPlannerConfig(kSeed, kIterations, kTimeBudget));
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  const PathResult first = planner.plan(kStart, kGoal);
  ASSERT_EQ(first.status, PathStatus::kExactSolution);
  for (int i = 0; i < 4; ++i) {
    planner.clear();
    EXPECT_EQ(planner.roadmapVertices(), 0u);
    const PathResult r = planner.plan(kStart, kGoal);
    ASSERT_EQ(r.status, PathStatus::kExactSolution);
    EXPECT_EQ(r.path, first.path);
  }
}

TEST(PathPlanner, SameSeedSamePath) {
  const WallWorld world(true);
  const PathPlannerConfig c = seededPlannerConfig(kSeed, kIterations, kTimeBudget);
  PathPlanner a(c), b(c);
  ASSERT_TRUE(a.setMap(&world.collision(), world.bounds()));
  ASSERT_TRUE(b.setMap(&world.collision(), world.bounds()));
  const PathResult ra = a.plan(kStart, kGoal), rb = b.plan(kStart, kGoal);
  ASSERT_EQ(ra.status, PathStatus::kExactSolution);
  EXPECT_EQ(ra.path, rb.path);
  EXPECT_EQ(ra.length, rb.length);
}

TEST(PathPlanner, RoadmapPersistsAndMapChangesAreRechecked) {
  WallWorld world(true);
  PathPlanner planner(seededPlannerConfig(kSeed, kIterations, kTimeBudget));
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  const PathResult first = planner.plan(kStart, kGoal);
  ASSERT_EQ(first.status, PathStatus::kExactSolution);
  const size_t vertices = planner.roadmapVertices();
  EXPECT_GT(vertices, 2u);
  // A second query reuses the roadmap.
  const PathResult second = planner.plan(Eigen::Vector4d(-4.0, 3.0, 2.5, 0.0), Eigen::Vector4d(4.0, 3.0, 2.5, 0.0));
  ASSERT_EQ(second.status, PathStatus::kExactSolution);
  EXPECT_GE(planner.roadmapVertices(), vertices);
  std::printf("second query on the kept roadmap: %.4f s\n", second.seconds);
  // Closing the gap invalidates the edges through it.
  world.closeGap();
  planner.mapChanged();
  const PathResult closed = planner.plan(kStart, kGoal);
  EXPECT_FALSE(hasPath(closed.status)) << toString(closed.status);
  EXPECT_TRUE(closed.path.empty());
}

namespace {

// Valid query points on both sides of the wall, in a fixed pseudo-random order.
std::vector<Eigen::Vector4d> queryPoints(const CollisionMap& map, size_t n, unsigned int seed) {
  std::vector<Eigen::Vector4d> points;
  unsigned int state = seed;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return (state >> 8) / static_cast<double>(1u << 24);
  };
  while (points.size() < n) {
    const Eigen::Vector4d p(-4.8 + 9.6 * next(), -4.8 + 9.6 * next(), 1.2 + 2.6 * next(), 0.0);
    if (map.isFree(p.head<3>(), 1.2)) points.push_back(p);
  }
  return points;
}

PathPlannerConfig searchConfig(QuerySearch search) {
  PathPlannerConfig c = seededPlannerConfig(kSeed, kIterations, kTimeBudget);
  c.time_budget = 1e3;  // only the iterations bound it, so both grow alike
  c.iteration_budget = 600;
  c.search = search;
  c.simplify = false;  // compare the roadmap paths themselves
  return c;
}

}  // namespace

// Our lazy A* and OMPL's LazyPRM::constructSolution, on roadmaps grown from
// the same seed by the same queries, return the same path lengths and leave
// the same roadmap, also across a map change that closes the gap.
TEST(PathPlanner, FastSearchMatchesOmplSearch) {
  WallWorld world(true);
  PathPlanner fast(searchConfig(QuerySearch::kFast)), ompl(searchConfig(QuerySearch::kOmplSearch));
  bool same = true;
  ASSERT_TRUE(fast.setMap(&world.collision(), world.bounds()));
  ASSERT_TRUE(ompl.setMap(&world.collision(), world.bounds()));
  const std::vector<Eigen::Vector4d> points = queryPoints(world.collision(), 30, 3);
  size_t paths = 0;
  for (int phase = 0; phase < 2; ++phase) {
    for (size_t i = 0; i + 1 < points.size(); i += 2) {
      const PathResult a = fast.plan(points[i], points[i + 1]), b = ompl.plan(points[i], points[i + 1]);
      ASSERT_EQ(a.status, b.status) << "query " << i << " phase " << phase;
      EXPECT_NEAR(a.length, b.length, 1e-9) << "query " << i << " phase " << phase;
      if (same) {
        EXPECT_EQ(fast.roadmapVertices(), ompl.roadmapVertices()) << "query " << i << " phase " << phase;
      }
      same = same && fast.roadmapVertices() == ompl.roadmapVertices();
      if (hasPath(a.status)) {
        expectCollisionFree(world.collision(), a, 1.0);
        ++paths;
      }
    }
    world.closeGap();
    fast.mapChanged();
    ompl.mapChanged();
  }
  EXPECT_GT(paths, 15u);
}

// A kept roadmap routes through the gap; a box then blocks the part of the
// gap the path used: after mapChanged() the query re-checks the cached
// edges and goes around through what is left of the gap.
TEST(PathPlanner, BlockedEdgeIsRecheckedAndAvoided) {
  WallWorld world(true);
  PathPlanner planner(seededPlannerConfig(kSeed, kIterations, kTimeBudget));
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  const Eigen::Vector4d start(-4.0, 2.0, 2.5, 0.0), goal(4.0, 2.0, 2.5, 0.0);
  const PathResult first = planner.plan(start, goal);
  ASSERT_EQ(first.status, PathStatus::kExactSolution);
  const PathResult again = planner.plan(start, goal);
  ASSERT_EQ(again.status, PathStatus::kExactSolution);
  EXPECT_NEAR(again.length, first.length, 0.5);
  world.addBox(Eigen::Vector3d(-0.5, 0.5, 0.0), Eigen::Vector3d(0.5, 2.75, 5.0));
  planner.mapChanged();
  const size_t vertices = planner.roadmapVertices();
  const PathResult around = planner.plan(start, goal);
  ASSERT_EQ(around.status, PathStatus::kExactSolution) << toString(around.status);
  expectCollisionFree(world.collision(), around, 1.0);
  EXPECT_GT(around.length, first.length);
  EXPECT_GE(planner.roadmapVertices() + 10, vertices);  // kept, not rebuilt
  for (size_t k = 0; k + 1 < around.path.size(); ++k) {
    const Eigen::Vector3d a = around.path[k].head<3>(), b = around.path[k + 1].head<3>();
    if ((a.x() < 0.0) != (b.x() < 0.0)) {
      EXPECT_GT((a + (-a.x() / (b.x() - a.x())) * (b - a)).y(), 2.75 + 1.0);
    }
  }
}

TEST(PathPlanner, SameSeedSameQueriesRepeatExactly) {
  const WallWorld world(true);
  const std::vector<Eigen::Vector4d> points = queryPoints(world.collision(), 12, 5);
  std::vector<std::vector<Eigen::Vector4d>> runs[2];
  for (auto& run : runs) {
    PathPlanner planner(seededPlannerConfig(kSeed, kIterations, kTimeBudget));
    ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
    for (size_t i = 0; i + 1 < points.size(); ++i) run.push_back(planner.plan(points[i], points[i + 1]).path);
  }
  EXPECT_EQ(runs[0], runs[1]);
}

// With the wall closed no query succeeds; each plan() adds its start and
// goal and at most iteration_budget samples, the same on every run.
TEST(PathPlanner, IterationBudgetBoundsTheRoadmapGrowth) {
  const WallWorld world(false);
  size_t grown[2] = {0, 0};
  for (size_t& g : grown) {
    PathPlannerConfig c = seededPlannerConfig(kSeed, kIterations, kTimeBudget);
    c.iteration_budget = 200;
    PathPlanner planner(c);
    ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
    for (int i = 0; i < 3; ++i) {
      const size_t before = planner.roadmapVertices();
      EXPECT_EQ(planner.plan(kStart, kGoal).status, PathStatus::kNoSolution);
      EXPECT_LE(planner.roadmapVertices(), before + 200 + 2);
      EXPECT_GT(planner.roadmapVertices(), before + 100);
    }
    g = planner.roadmapVertices();
  }
  EXPECT_EQ(grown[0], grown[1]);
}

TEST(PathPlannerOracle, StraightWhenFreeLongerAroundTheWall) {
  const WallWorld world(true);
  PathPlanner planner(seededPlannerConfig(kSeed, kIterations, kTimeBudget));
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  ASSERT_EQ(planner.plan(kStart, kGoal).status, PathStatus::kExactSolution);
  const auto oracle = planner.distanceOracle();
  const Eigen::Vector3d a = kStart.head<3>(), b = kGoal.head<3>();
  const double around = oracle(a, b);
  EXPECT_TRUE(std::isfinite(around));
  // Through the gap (y >= 1 m plus the radius) on both sides of the wall.
  EXPECT_GT(around, 2.0 * std::hypot(4.0, 5.0));
  EXPECT_EQ(oracle(b, a), around);
  EXPECT_EQ(oracle(a, a), 0.0);
  const Eigen::Vector3d same_side(-3.0, 2.0, 3.0);
  EXPECT_NEAR(oracle(a, same_side), (a - same_side).norm(), 1e-12);
  // Never below the straight line, on pairs on either side.
  const std::vector<Eigen::Vector4d> points = queryPoints(world.collision(), 30, 9);
  size_t finite = 0;
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const double d = oracle(points[i].head<3>(), points[i + 1].head<3>());
    EXPECT_GE(d, (points[i] - points[i + 1]).head<3>().norm() - 1e-12);
    finite += std::isfinite(d);
  }
  EXPECT_GT(finite, points.size() / 2);
}

// The oracle flags what it finds blocked without removing it; once the map
// changes again those flags are out of date: the reopened gap is used.
TEST(PathPlannerOracle, BlockedFlagsExpireWithTheMap) {
  WallWorld world(true);
  PathPlanner planner(seededPlannerConfig(kSeed, kIterations, kTimeBudget));
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  const PathResult first = planner.plan(kStart, kGoal);
  ASSERT_EQ(first.status, PathStatus::kExactSolution);
  const Eigen::Vector3d a = kStart.head<3>(), b = kGoal.head<3>();
  const double open = planner.distanceOracle()(a, b);
  ASSERT_TRUE(std::isfinite(open));
  world.closeGap();
  planner.mapChanged();
  EXPECT_TRUE(std::isinf(planner.distanceOracle()(a, b)));
  world.openGap();
  planner.mapChanged();
  EXPECT_NEAR(planner.distanceOracle()(a, b), open, 1e-9);
}

TEST(PathPlannerOracle, InfiniteAcrossAClosedWall) {
  const WallWorld world(false);
  PathPlannerConfig c = seededPlannerConfig(kSeed, kIterations, kTimeBudget);
  c.iteration_budget = 1500;
  PathPlanner planner(c);
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()));
  EXPECT_EQ(planner.plan(kStart, kGoal).status, PathStatus::kNoSolution);  // grows the roadmap on both sides
  const auto oracle = planner.distanceOracle();
  EXPECT_TRUE(std::isinf(oracle(kStart.head<3>(), kGoal.head<3>())));
  EXPECT_TRUE(std::isinf(oracle(kGoal.head<3>(), kStart.head<3>())));
  const Eigen::Vector3d left(-4.0, 3.0, 2.5), right(4.0, 3.0, 2.5);
  EXPECT_TRUE(std::isinf(oracle(left, right)));
  EXPECT_NEAR(oracle(kStart.head<3>(), left), 6.0, 1e-12);
}
