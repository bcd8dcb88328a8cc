// ReachableSpace: the flood fill holds what the path planner can reach and
// nothing across a closed wall; the explorer skips targets outside it.
#include "surface_nbv/planning/reachable_space.h"

#include <gtest/gtest.h>

#include <cmath>

#include "planning_test_worlds.h"
#include "surface_nbv/planning/path_planner.h"

using namespace surface_nbv;

TEST(ReachableSpace, GapConnectsBothSidesAClosedWallSeparatesThem) {
  WallWorld world(true);
  ReachableSpace space;
  const Eigen::Vector3d left(-3.0, -3.0, 2.5), right(3.0, -3.0, 2.5);
  space.fill(world.collision(), world.bounds(), left, 1.0);
  ASSERT_TRUE(space.seeded());
  EXPECT_TRUE(space.reachable(left));
  EXPECT_TRUE(space.reachable(right));
  EXPECT_GT(space.size(), 100u);

  world.closeGap();
  space.fill(world.collision(), world.bounds(), left, 1.0);
  ASSERT_TRUE(space.seeded());
  EXPECT_TRUE(space.reachable(left));
  EXPECT_FALSE(space.reachable(right));
  EXPECT_FALSE(space.reachable(Eigen::Vector3d(50.0, 0.0, 2.0))) << "outside the grid";
  // The planner agrees: no path across the closed wall.
  PathPlanner planner(seededPlannerConfig(3, 4000, 5.0));
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()).ok());
  const PathResult r = planner.plan(Eigen::Vector4d(left.x(), left.y(), left.z(), 0.0),
                                    Eigen::Vector4d(right.x(), right.y(), right.z(), 0.0));
  EXPECT_FALSE(hasPath(r.status));
}

TEST(ReachableSpace, EveryPointOfAPlannedPathIsInside) {
  WallWorld world(true);
  PathPlanner planner(seededPlannerConfig(3, 4000, 5.0));
  ASSERT_TRUE(planner.setMap(&world.collision(), world.bounds()).ok());
  const Eigen::Vector4d a(-3.0, -3.0, 2.5, 0.0), b(3.0, -4.0, 1.5, 0.0);
  const PathResult r = planner.plan(a, b);
  ASSERT_TRUE(hasPath(r.status));
  ReachableSpace space;
  const double half_diagonal = 0.5 * std::sqrt(3.0) * world.collision().cellSize();
  space.fill(world.collision(), world.bounds(), a.head<3>(), 1.0, half_diagonal);
  for (size_t i = 1; i < r.path.size(); ++i) {
    const Eigen::Vector3d p = r.path[i - 1].head<3>(), q = r.path[i].head<3>();
    for (int s = 0; s <= 20; ++s) {
      const Eigen::Vector3d x = p + (q - p) * (s / 20.0);
      EXPECT_TRUE(space.reachable(x)) << x.transpose();
    }
  }
}

TEST(ReachableSpace, NoClearSeedMeansNothingIsKnown) {
  WallWorld world(false);
  ReachableSpace space;
  // Inside the wall, and no clear cell within 0.1 m: every answer is true.
  space.fill(world.collision(), world.bounds(), Eigen::Vector3d(0.0, -3.0, 2.5), 1.0, 0.0, 0.1);
  EXPECT_FALSE(space.seeded());
  EXPECT_TRUE(space.reachable(Eigen::Vector3d(3.0, -3.0, 2.5)));
  // With the default seed radius the nearest clear cells start the fill.
  space.fill(world.collision(), world.bounds(), Eigen::Vector3d(0.0, -3.0, 2.5), 1.0);
  EXPECT_TRUE(space.seeded());
}
