// ReachableSpace: the flood fill holds what the path planner can reach and
// nothing across a closed wall; the explorer skips targets outside it.
#include "surface_nbv/planning/reachable_space.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

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

namespace {

// The fill as written first: a flood over cellCentreDistance() queries, or
// with `planner_test` over isFree() queries at the cells' centres (as the
// oracle's own flood was written).
std::vector<uint8_t> referenceFill(const CollisionMap& map, const Eigen::Vector3i& start, double clear,
                                   const Eigen::Vector3d& origin = Eigen::Vector3d::Zero(), bool planner_test = false) {
  const Eigen::Vector3i n = map.gridCells();
  auto at = [&](const Eigen::Vector3i& c) { return static_cast<size_t>((c.x() * n.y() + c.y()) * n.z() + c.z()); };
  std::vector<uint8_t> in(static_cast<size_t>(n.prod()), 0);
  auto isClear = [&](const Eigen::Vector3i& c) {
    if (!planner_test) return map.cellCentreDistance(c) >= clear;
    return map.isFree(origin + map.cellSize() * (c.cast<double>().array() + 0.5).matrix(), clear);
  };
  auto open = [&](const Eigen::Vector3i& c) {
    return (c.array() >= 0).all() && (c.array() < n.array()).all() && in[at(c)] == 0 && isClear(c);
  };
  std::vector<Eigen::Vector3i> stack;
  if (open(start)) {
    in[at(start)] = 1;
    stack.push_back(start);
  }
  while (!stack.empty()) {
    const Eigen::Vector3i c = stack.back();
    stack.pop_back();
    for (int a = 0; a < 3; ++a) {
      for (int s = -1; s <= 1; s += 2) {
        Eigen::Vector3i d = c;
        d[a] += s;
        if (!open(d)) continue;
        in[at(d)] = 1;
        stack.push_back(d);
      }
    }
  }
  return in;
}

}  // namespace

// The wall world with its gap, flooded from (-3, -3, 2.5) (grid cell `start`).
class FloodFromTheLeft : public ::testing::Test {
 protected:
  FloodFromTheLeft() : map(world.collision()), n(map.gridCells()) {
    for (int a = 0; a < 3; ++a) {
      start[a] = static_cast<int>(std::floor((from[a] - world.bounds().min[a]) / map.cellSize()));
    }
  }
  // The cells where `space` and the reference flood `expected` disagree, and
  // in `count` the reference's cells.
  size_t mismatches(const ReachableSpace& space, const std::vector<uint8_t>& expected, size_t* count) const {
    size_t wrong = 0;
    *count = 0;
    for (int x = 0; x < n.x(); ++x)
      for (int y = 0; y < n.y(); ++y)
        for (int z = 0; z < n.z(); ++z) {
          const bool want = expected[static_cast<size_t>((x * n.y() + y) * n.z() + z)] != 0;
          *count += want ? 1 : 0;
          wrong += space.filled(Eigen::Vector3i(x, y, z)) != want ? 1 : 0;
        }
    return wrong;
  }

  WallWorld world{true};
  const CollisionMap& map;
  const Eigen::Vector3d from{-3.0, -3.0, 2.5};
  const Eigen::Vector3i n;
  Eigen::Vector3i start;
};

// The fill reads the transform in one pass (CollisionMap::clearCells) and
// floods a byte per cell: it fills exactly the cells the flood over
// distance queries does, also at clearances that fall on a cell distance.
TEST_F(FloodFromTheLeft, FillsExactlyTheCellsOfAFloodOverDistanceQueries) {
  const double h = map.cellSize();
  size_t differing_sizes = 0, previous = 0;
  for (const double clear : {0.0, 0.5, 1.0, 2.0 * h, std::sqrt(5.0) * h, 3.0 * h, 1.3}) {
    ReachableSpace space;
    space.fill(map, world.bounds(), from, clear);
    ASSERT_TRUE(space.seeded()) << clear;
    size_t count = 0;
    const size_t wrong = mismatches(space, referenceFill(map, start, clear), &count);
    EXPECT_EQ(wrong, 0u) << "clearance " << clear;
    EXPECT_EQ(space.size(), count) << "clearance " << clear;
    EXPECT_GT(count, 100u) << clear;
    differing_sizes += count != previous ? 1 : 0;
    previous = count;
  }
  EXPECT_GE(differing_sizes, 4u);  // the clearances do cut the free space differently
  // The mask itself, also beyond the transform's cap (max_distance).
  const double kCap = CollisionConfig().max_distance;
  std::vector<uint8_t> mask;
  for (const double clear : {1.0, kCap - 0.5 * h, kCap,
                             kCap + 2.0 * h}) {
    map.clearCells(clear, &mask);
    ASSERT_EQ(mask.size(), static_cast<size_t>(n.prod()));
    size_t wrong = 0, passed = 0;
    for (int x = 0; x < n.x(); ++x)
      for (int y = 0; y < n.y(); ++y)
        for (int z = 0; z < n.z(); ++z) {
          const bool want = map.cellCentreDistance(Eigen::Vector3i(x, y, z)) >= clear;
          passed += want ? 1 : 0;
          wrong += (mask[static_cast<size_t>((x * n.y() + y) * n.z() + z)] != 0) != want ? 1 : 0;
        }
    EXPECT_EQ(wrong, 0u) << "clearance " << clear;
    EXPECT_GT(passed, 0u) << "clearance " << clear;
  }
  map.clearCells(std::nan(""), &mask);
  EXPECT_EQ(mask.size(), static_cast<size_t>(n.prod()));
  EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), 0) << "a NaN clearance clears nothing";
  map.clearCells(1e12, &mask);
  EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), 0);
  map.clearCells(-1.0, &mask);
  EXPECT_EQ(std::count(mask.begin(), mask.end(), 1), n.prod()) << "every cell is at least 0 m clear";
}

// Clear::kPlannerTest floods exactly the cells whose centre passes the path
// planner's isFree() test, fewer than the centre distances pass (the
// obstacles' cubes and the bounds' faces count), and the explorer's default
// fill is the centre-distance one.
TEST_F(FloodFromTheLeft, PlannerTestFloodsTheCellsWhoseCentreIsFree) {
  for (const double clear : {0.5, 1.0, 1.3}) {
    ReachableSpace planner_test, centres;
    planner_test.fill(map, world.bounds(), from, clear, 0.0, 2.0, ReachableSpace::Clear::kPlannerTest);
    centres.fill(map, world.bounds(), from, clear);
    ASSERT_TRUE(planner_test.seeded()) << clear;
    size_t count = 0, centre_count = 0;
    const size_t wrong = mismatches(planner_test, referenceFill(map, start, clear, world.bounds().min, true), &count);
    const size_t centre_wrong = mismatches(centres, referenceFill(map, start, clear), &centre_count);
    EXPECT_EQ(wrong, 0u) << "clearance " << clear;
    EXPECT_EQ(planner_test.size(), count) << "clearance " << clear;
    EXPECT_GT(count, 100u) << clear;
    EXPECT_EQ(centre_wrong, 0u) << "clearance " << clear;
    EXPECT_LT(count, centre_count) << "clearance " << clear;
  }
}

// corridor(): from the seed cell through the gap to the target's cell, one
// cell per step, every step a filled cell, as short as a breadth-first
// search over the reference flood's cells says; nothing across a closed wall.
TEST_F(FloodFromTheLeft, CorridorIsAShortestWayThroughTheFilledCells) {
  const double clear = 1.0;
  ReachableSpace space;
  space.fill(map, world.bounds(), from, clear);
  const Eigen::Vector3d to(3.0, -3.0, 2.5);
  ASSERT_TRUE(space.reachable(to));
  std::vector<Eigen::Vector3d> way;
  ASSERT_TRUE(space.corridor(to, &way));
  ASSERT_GE(way.size(), 2u);
  const double h = map.cellSize();
  const auto cellOf = [&](const Eigen::Vector3d& p) {
    return ((p - world.bounds().min) / h).array().floor().cast<int>().matrix().eval();
  };
  EXPECT_EQ(cellOf(way.front()), start);
  EXPECT_EQ(cellOf(way.back()), cellOf(to));
  for (size_t k = 0; k < way.size(); ++k) {
    EXPECT_TRUE(space.filled(cellOf(way[k]))) << k;
    if (k > 0) {
      EXPECT_NEAR((way[k] - way[k - 1]).norm(), h, 1e-9) << k;
    }
  }
  // Breadth-first distances over the reference flood's cells.
  const std::vector<uint8_t> in = referenceFill(map, start, clear);
  auto at = [&](const Eigen::Vector3i& c) { return static_cast<size_t>((c.x() * n.y() + c.y()) * n.z() + c.z()); };
  std::vector<int> dist(in.size(), -1);
  std::vector<Eigen::Vector3i> queue{start};
  dist[at(start)] = 0;
  for (size_t head = 0; head < queue.size(); ++head) {
    const Eigen::Vector3i c = queue[head];
    for (int a = 0; a < 3; ++a)
      for (int s = -1; s <= 1; s += 2) {
        Eigen::Vector3i d = c;
        d[a] += s;
        if ((d.array() < 0).any() || (d.array() >= n.array()).any() || !in[at(d)] || dist[at(d)] >= 0) continue;
        dist[at(d)] = dist[at(c)] + 1;
        queue.push_back(d);
      }
  }
  ASSERT_GT(dist[at(cellOf(to))], 0);
  EXPECT_EQ(static_cast<int>(way.size()) - 1, dist[at(cellOf(to))]);
  // The way crosses the wall's plane only at the gap: it is longer than the
  // straight line between its ends.
  EXPECT_GT((way.size() - 1) * h, (way.back() - way.front()).norm() + 1.0);

  world.closeGap();
  space.fill(world.collision(), world.bounds(), from, clear);
  EXPECT_FALSE(space.corridor(to, &way));
  EXPECT_TRUE(way.empty());
  ReachableSpace unfilled;
  EXPECT_FALSE(unfilled.corridor(to, &way)) << "nothing seeded";
}

// PathPlanner::plan with the corridor as its guide: the path follows it
// (from_guide), is collision-free, and costs the lattice fewer nodes than
// the lattice's own search from scratch; a guide the planner cannot follow
// (straight through the wall) falls back to the lattice.
TEST_F(FloodFromTheLeft, PlannerFollowsTheCorridorAndFallsBackFromABadGuide) {
  PathPlannerConfig config = seededPlannerConfig(3, 0, 10.0);
  config.lattice_step = 0.3;
  const Eigen::Vector4d a(from.x(), from.y(), from.z(), 0.0), b(3.0, -3.0, 2.5, 0.0);
  const auto fresh = [&] {
    auto p = std::make_unique<PathPlanner>(config);
    EXPECT_TRUE(p->setMap(&map, world.bounds()).ok());
    return p;
  };
  ReachableSpace space;
  auto probe = fresh();
  space.fill(map, world.bounds(), from, probe->clearance());
  std::vector<Eigen::Vector3d> guide;
  ASSERT_TRUE(space.corridor(b.head<3>(), &guide));

  const PathResult alone = fresh()->plan(a, b);
  ASSERT_TRUE(hasPath(alone.status));
  ASSERT_TRUE(alone.from_lattice);
  auto planner = fresh();
  const PathResult guided = planner->plan(a, b, std::numeric_limits<double>::infinity(), &guide);
  ASSERT_TRUE(hasPath(guided.status)) << toString(guided.status);
  EXPECT_TRUE(guided.from_guide);
  EXPECT_FALSE(guided.from_lattice);
  EXPECT_LT(guided.lattice_nodes, alone.lattice_nodes);
  EXPECT_TRUE(guided.path.front().head<3>().isApprox(a.head<3>()));
  EXPECT_TRUE(guided.path.back().head<3>().isApprox(b.head<3>()));
  const double radius = config.collision_radius;
  for (size_t k = 1; k < guided.path.size(); ++k) {
    const Eigen::Vector3d p = guided.path[k - 1].head<3>(), q = guided.path[k].head<3>();
    const int steps = static_cast<int>(std::ceil((q - p).norm() / 0.02));
    for (int s = 0; s <= steps; ++s) {
      const Eigen::Vector3d x = p + (q - p) * (static_cast<double>(s) / std::max(steps, 1));
      ASSERT_TRUE(map.isFree(x, radius)) << "segment " << k << " at " << x.transpose();
    }
  }
  EXPECT_LT(guided.length, 1.5 * alone.length);
  // The way it found joined the roadmap: asked again, the graph answers.
  const PathResult again = planner->plan(a, b, std::numeric_limits<double>::infinity(), &guide);
  ASSERT_TRUE(hasPath(again.status));
  EXPECT_FALSE(again.from_guide);

  // Straight through the wall: the point in it is skipped, the lattice
  // repair from the start to the goal needs as many nodes as the search
  // alone, more than its tenth of the budget, so the lattice takes over.
  config.lattice_max_nodes = alone.lattice_nodes + 10;
  const std::vector<Eigen::Vector3d> through_wall{a.head<3>(), Eigen::Vector3d(0.0, -3.0, 2.5), b.head<3>()};
  const PathResult bad = fresh()->plan(a, b, std::numeric_limits<double>::infinity(), &through_wall);
  ASSERT_TRUE(hasPath(bad.status));
  EXPECT_FALSE(bad.from_guide);
  EXPECT_TRUE(bad.from_lattice);
  EXPECT_GT(bad.lattice_nodes, alone.lattice_nodes) << "the failed repair's nodes count too";
}
