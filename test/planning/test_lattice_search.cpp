// The lattice A* (lattice_search.h) on its own, and as the path planner's
// fallback when the roadmap misses a narrow slot.
#include "surface_nbv/planning/lattice_search.h"

#include <cmath>

#include <gtest/gtest.h>

#include "planning_test_worlds.h"

namespace surface_nbv {
namespace {

using Eigen::Vector3d;

double lengthOf(const std::vector<Vector3d>& path) {
  double length = 0.0;
  for (size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length;
}

// Free except a ball of radius 1.5 around the origin, sampled every 5 cm.
bool outsideBall(const Vector3d& a, const Vector3d& b) {
  const int n = 1 + static_cast<int>((b - a).norm() / 0.05);
  for (int i = 1; i <= n; ++i)
    if ((a + (b - a) * (static_cast<double>(i) / n)).norm() < 1.5) return false;
  return true;
}

TEST(LatticeSearch, FindsTheShortLatticePathAroundAnObstacle) {
  const Vector3d start(-3.0, 0.1, 0.0), goal(3.05, -0.2, 0.1);
  const LatticeSearchResult r = latticeSearch(start, goal, 0.25, 100000, outsideBall, nullptr);
  ASSERT_TRUE(r.found);
  EXPECT_FALSE(r.stopped);
  EXPECT_EQ(r.path.front(), start);
  EXPECT_EQ(r.path.back(), goal);
  for (size_t i = 1; i < r.path.size(); ++i) EXPECT_TRUE(outsideBall(r.path[i - 1], r.path[i])) << i;
  // Around a ball of radius 1.5 between points 3 m from its centre: at least
  // the straight 6 m, and the lattice detour stays within a third of it.
  EXPECT_GT(lengthOf(r.path), 6.3);
  EXPECT_LT(lengthOf(r.path), 8.0);
  // Same inputs, same path.
  const LatticeSearchResult again = latticeSearch(start, goal, 0.25, 100000, outsideBall, nullptr);
  EXPECT_EQ(again.path, r.path);
}

TEST(LatticeSearch, EnclosedGoalExhaustsTheSpaceOrTheBudget) {
  // The goal sits inside a closed shell (radius 1 to 2) around the origin.
  const auto shell = [](const Vector3d& a, const Vector3d& b) {
    const int n = 1 + static_cast<int>((b - a).norm() / 0.05);
    for (int i = 0; i <= n; ++i) {
      const double r = (a + (b - a) * (static_cast<double>(i) / n)).norm();
      if (r > 1.0 && r < 2.0) return false;
    }
    // A finite world: |x|, |y|, |z| < 3.
    return (b.array().abs() < 3.0).all();
  };
  const LatticeSearchResult r = latticeSearch(Vector3d(-2.6, 0, 0), Vector3d(0.1, 0, 0), 0.5, 100000, shell, nullptr);
  EXPECT_FALSE(r.found);
  EXPECT_FALSE(r.stopped);  // the reachable lattice ran out
  EXPECT_GT(r.expanded, 50u);
  EXPECT_TRUE(r.path.empty());

  const LatticeSearchResult capped = latticeSearch(Vector3d(-2.6, 0, 0), Vector3d(0.1, 0, 0), 0.5, 20, shell, nullptr);
  EXPECT_FALSE(capped.found);
  EXPECT_TRUE(capped.stopped);
  EXPECT_LE(capped.expanded, 21u);

  int calls = 0;
  const LatticeSearchResult stopped = latticeSearch(Vector3d(-2.6, 0, 0), Vector3d(0.1, 0, 0), 0.5, 100000, shell,
                                                    [&calls] { return ++calls >= 1; });
  EXPECT_FALSE(stopped.found);
  EXPECT_TRUE(stopped.stopped);
  EXPECT_EQ(calls, 1);
}

TEST(LatticeSearch, RefusesBadInput) {
  EXPECT_FALSE(latticeSearch(Vector3d::Zero(), Vector3d::Ones(), 0.0, 10, outsideBall, nullptr).found);
  EXPECT_FALSE(latticeSearch(Vector3d(NAN, 0, 0), Vector3d::Ones(), 0.5, 10, outsideBall, nullptr).found);
  EXPECT_FALSE(latticeSearch(Vector3d(4, 0, 0), Vector3d(5, 0, 0), 0.5, 0, outsideBall, nullptr).found);
}

// The wall of WallWorld closed except for a slot 2.5 m wide: with the 1 m
// collision radius only a band about 0.4 m wide in its middle is valid,
// which a roadmap of a few samples does not hit and the lattice does,
// asked before the roadmap grows.
TEST(LatticeSearch, PlannerFallsBackToTheLatticeThroughANarrowSlot) {
  WallWorld world(true);
  world.addBox(Vector3d(-0.25, 0.9, -1.0), Vector3d(0.25, 2.1, 6.0));
  world.addBox(Vector3d(-0.25, 4.4, -1.0), Vector3d(0.25, 7.0, 6.0));
  const Eigen::Vector4d start(-3.5, -3.0, 2.5, 0.0), goal(3.5, -2.8, 2.4, 1.0);

  PathPlannerConfig config = seededPlannerConfig(3, 5, 10.0);
  PathPlanner sampled(config);
  ASSERT_TRUE(sampled.setMap(&world.collision(), world.bounds()).ok());
  const PathResult miss = sampled.plan(start, goal);
  ASSERT_EQ(miss.status, PathStatus::kNoSolution) << "the roadmap alone must miss the slot for this test to mean anything";
  EXPECT_EQ(miss.lattice_nodes, 0u);

  config.lattice_step = 0.25;
  for (int run = 0; run < 2; ++run) {
    PathPlanner planner(config);
    ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()).ok());
    const PathResult r = planner.plan(start, goal);
    ASSERT_EQ(r.status, PathStatus::kExactSolution) << toString(r.status);
    EXPECT_TRUE(r.from_lattice);
    EXPECT_GT(r.lattice_nodes, 0u);
    EXPECT_FALSE(r.roadmap_grew) << "the lattice is asked before the roadmap grows";
    EXPECT_LE(planner.roadmapVertices(), 2 + r.path.size()) << "the query's start and goal, and the way found";
    ASSERT_GE(r.path.size(), 2u);
    EXPECT_EQ(r.path.front().head<3>(), start.head<3>());
    EXPECT_EQ(r.path.back().head<3>(), goal.head<3>());
    EXPECT_NEAR(r.path.back().w(), 1.0, 1e-9);
    for (size_t i = 1; i < r.path.size(); ++i) {
      const Vector3d a = r.path[i - 1].head<3>(), b = r.path[i].head<3>();
      for (double f = 0.0; f <= 1.0; f += 0.01) {
        const Vector3d p = a + f * (b - a);
        ASSERT_TRUE(world.collision().isFree(p, 1.0)) << "segment " << i << " at " << p.transpose();
        if (std::abs(p.x()) < 0.3) {
          EXPECT_GT(p.y(), 2.1 + 0.9) << "through the slot";
        }
      }
    }
    EXPECT_LT(r.length, 16.0);  // the straight way through the slot centre is 14.3 m
    // The lattice's way joined the roadmap: the same query is answered from the graph.
    EXPECT_GT(planner.roadmapVertices(), 2u);
    const PathResult again = planner.plan(start, goal);
    ASSERT_EQ(again.status, PathStatus::kExactSolution);
    EXPECT_FALSE(again.from_lattice);
    EXPECT_FALSE(again.roadmap_grew);
    EXPECT_EQ(again.lattice_nodes, 0u);
    EXPECT_LE(again.length, r.length + 1e-9);
  }

  // A goal sealed off entirely: the fallback fails too and says so.
  world.addBox(Vector3d(-0.25, 2.0, -1.0), Vector3d(0.25, 4.5, 6.0));
  PathPlanner sealed(config);
  ASSERT_TRUE(sealed.setMap(&world.collision(), world.bounds()).ok());
  const PathResult none = sealed.plan(start, goal);
  EXPECT_EQ(none.status, PathStatus::kNoSolution);
  EXPECT_FALSE(none.from_lattice);
  EXPECT_GT(none.lattice_nodes, 0u);
  EXPECT_TRUE(none.roadmap_grew) << "then the roadmap grows";
}

// A caller's cap (the ROS planner's leg_time_budget) with a lattice bounded
// by wall time only: the lattice, asked before the roadmap grows, stops at
// half the cap and the growth searches in the rest.
TEST(LatticeSearch, LatticeLeavesTheRoadmapHalfOfACallersCap) {
  WallWorld world(false);  // no gap: neither search can reach the goal, both run to their limits
  const Eigen::Vector4d start(-3.5, -3.0, 2.5, 0.0), goal(3.5, -2.8, 2.4, 1.0);
  PathPlannerConfig config = seededPlannerConfig(3, 0, 30.0);  // no iteration bound
  config.lattice_step = 0.25;
  config.lattice_max_nodes = 100000000;  // the wall time stops it, not the node count
  PathPlanner planner(config);
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()).ok());
  const double cap = 1.0;
  const PathResult r = planner.plan(start, goal, cap);
  EXPECT_EQ(r.status, PathStatus::kTimeout) << toString(r.status);
  EXPECT_FALSE(r.from_lattice);
  EXPECT_GT(r.lattice_nodes, 0u);
  EXPECT_TRUE(r.roadmap_grew) << "the lattice spent the whole cap";
  EXPECT_GT(r.seconds, 0.9 * cap);
  EXPECT_LT(r.seconds, cap + 0.5);

  config.lattice_step = 0.0;  // without the lattice the roadmap keeps the whole cap
  PathPlanner alone(config);
  ASSERT_TRUE(alone.setMap(&world.collision(), world.bounds()).ok());
  const PathResult a = alone.plan(start, goal, cap);
  EXPECT_EQ(a.status, PathStatus::kTimeout) << toString(a.status);
  EXPECT_EQ(a.lattice_nodes, 0u);
  EXPECT_GT(a.seconds, 0.9 * cap);
}

// A start from which the lattice and then a growth found no way out grows
// the roadmap no more until the map changes; the lattice is still asked.
TEST(LatticeSearch, AStuckStartGrowsTheRoadmapOnceUntilTheMapChanges) {
  WallWorld world(false);  // no gap: the far side is sealed off
  const Eigen::Vector4d start(-3.5, -3.0, 2.5, 0.0), goal(3.5, -2.8, 2.4, 1.0), other(3.5, 2.0, 2.5, 0.0);
  PathPlannerConfig config = seededPlannerConfig(3, 300, 10.0);
  config.lattice_step = 0.5;
  config.lattice_max_nodes = 2000;
  PathPlanner planner(config);
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()).ok());
  const PathResult first = planner.plan(start, goal);
  EXPECT_EQ(first.status, PathStatus::kNoSolution);
  EXPECT_GT(first.lattice_nodes, 0u);
  EXPECT_TRUE(first.roadmap_grew);
  const size_t grown = planner.roadmapVertices();
  EXPECT_GT(grown, 100u);
  const PathResult second = planner.plan(start, other);
  EXPECT_EQ(second.status, PathStatus::kNoSolution);
  EXPECT_GT(second.lattice_nodes, 0u) << "the lattice is still asked";
  EXPECT_FALSE(second.roadmap_grew);
  EXPECT_LE(planner.roadmapVertices(), grown + 2) << "only the query's start and goal";
  // From elsewhere the roadmap grows as before, and from the same start once the map changed.
  const PathResult elsewhere = planner.plan(Eigen::Vector4d(-3.0, 2.0, 2.5, 0.0), goal);
  EXPECT_TRUE(elsewhere.roadmap_grew);
  planner.mapChanged();
  const PathResult changed = planner.plan(start, other);
  EXPECT_TRUE(changed.roadmap_grew);
  // A way that exists is still found from a stuck start.
  const PathResult near = planner.plan(start, Eigen::Vector4d(-3.5, 2.0, 2.5, 0.0));
  EXPECT_EQ(near.status, PathStatus::kExactSolution);
}

TEST(LatticeSearch, PlannerConfigValidatesTheLatticeKeys) {
  PathPlannerConfig c;
  c.lattice_step = -0.1;
  EXPECT_NE(c.validate().message().find("lattice_step"), std::string::npos);
  c.lattice_step = 0.25;
  c.lattice_max_nodes = 0;
  EXPECT_NE(c.validate().message().find("lattice_max_nodes"), std::string::npos);
}

}  // namespace
}  // namespace surface_nbv
