// restartLeg: a leg decided while the UAV flew on starts where the UAV is.
#include "surface_nbv/planning/leg_start.h"

#include <gtest/gtest.h>

#include "planning_test_worlds.h"

using namespace surface_nbv;

namespace {

constexpr double kClearance = 1.05;

// A leg on the UAV's side of the WallWorld wall (x < 0): from (-4, -3) north
// to (-4, 3) in 1 m steps, then along the wall's gap.
std::vector<Eigen::Vector4d> northLeg() {
  std::vector<Eigen::Vector4d> leg;
  for (int y = -3; y <= 3; ++y) leg.emplace_back(-4.0, y, 2.5, M_PI / 2);
  return leg;
}

TEST(LegStart, UavStillAtTheStartKeepsTheLeg) {
  WallWorld world(true);
  std::vector<Eigen::Vector4d> leg = northLeg();
  const std::vector<Eigen::Vector4d> before = leg;
  EXPECT_EQ(restartLeg(Eigen::Vector4d(-4.1, -3.1, 2.5, 0.0), world.collision(), kClearance, 3.0, 0.25, &leg),
            LegStart::kUnchanged);
  EXPECT_EQ(leg, before);
}

TEST(LegStart, UavThatFlewOnJoinsTheFarthestPointInReach) {
  WallWorld world(true);
  std::vector<Eigen::Vector4d> leg = northLeg();
  // The UAV flew on, 1.1 m north-west of the leg's start; the leg's first
  // 3 m (to y = 0) are in reach, and the straight way there is clear.
  const Eigen::Vector4d now(-4.5, -2.0, 2.5, 0.3);
  ASSERT_EQ(restartLeg(now, world.collision(), kClearance, 3.0, 0.25, &leg), LegStart::kJoined);
  ASSERT_EQ(leg.size(), 1u + 4u) << "now, then the leg from y = 0";
  EXPECT_EQ(leg.front(), now);
  EXPECT_DOUBLE_EQ(leg[1].y(), 0.0);
  EXPECT_EQ(leg.back(), northLeg().back());
  // With 0.5 m of reach only the leg's first point is a candidate.
  leg = northLeg();
  ASSERT_EQ(restartLeg(now, world.collision(), kClearance, 0.5, 0.25, &leg), LegStart::kJoined);
  ASSERT_EQ(leg.size(), 1u + 7u);
  EXPECT_EQ(leg[1], northLeg().front());
}

TEST(LegStart, AWallBetweenTheUavAndTheLegLeavesItBlocked) {
  WallWorld world(false);  // closed wall at x = 0
  std::vector<Eigen::Vector4d> leg = northLeg();
  const std::vector<Eigen::Vector4d> before = leg;
  // The UAV is on the other side of the wall (as a stale start never is, but
  // the segment test must see it).
  EXPECT_EQ(restartLeg(Eigen::Vector4d(3.0, -3.0, 2.5, 0.0), world.collision(), kClearance, 3.0, 0.25, &leg),
            LegStart::kBlocked);
  EXPECT_EQ(leg, before);
}

TEST(LegStart, SegmentsNearAnObstacleAreNotClear) {
  WallWorld world(false);
  EXPECT_TRUE(segmentClear(world.collision(), Eigen::Vector3d(-4, -3, 2.5), Eigen::Vector3d(-4, 3, 2.5), kClearance));
  // Parallel to the wall at 0.8 m: closer than the clearance.
  EXPECT_FALSE(segmentClear(world.collision(), Eigen::Vector3d(-1.05, -3, 2.5), Eigen::Vector3d(-1.05, 3, 2.5), kClearance));
  EXPECT_FALSE(segmentClear(world.collision(), Eigen::Vector3d(-4, 0, 2.5), Eigen::Vector3d(4, 0, 2.5), kClearance));
}

}  // namespace
