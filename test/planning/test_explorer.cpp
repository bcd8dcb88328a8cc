// The Fig. 1 replanning loop: full recomputation, local updates, legs,
// blacklisting, path checks and the stop reasons.
#include "surface_nbv/planning/explorer.h"

#include <limits>

#include <gtest/gtest.h>

#include "planning_test_worlds.h"

using namespace surface_nbv;

namespace {

// A frontier whose clusters are given as lists of viewpoint positions; one
// ISE per viewpoint, every ISE inside C_ins, every gain positive.
Frontier makeFrontier(const std::vector<std::vector<Eigen::Vector3d>>& clusters) {
  Frontier f;
  for (const auto& positions : clusters) {
    Cluster c;
    for (const Eigen::Vector3d& p : positions) {
      Ise ise;
      ise.position = p + Eigen::Vector3d(1.0, 0.0, 0.0);
      ise.viewpoint = static_cast<int32_t>(f.viewpoints.size());
      f.ises.push_back(ise);
      Viewpoint v;
      v.position = p;
      v.cluster = static_cast<int32_t>(f.clusters.size());
      v.visible = {static_cast<uint32_t>(f.ises.size() - 1)};
      c.viewpoints.push_back(static_cast<uint32_t>(f.viewpoints.size()));
      f.viewpoints.push_back(v);
    }
    c.visible_ises = positions.size();
    c.gain = 0.1 * positions.size();
    f.clusters.push_back(c);
  }
  return f;
}

PathPlannerConfig pathConfig() {
  PathPlannerConfig c;
  c.time_budget = 10.0;
  c.iteration_budget = 2000;
  c.seed = 3;
  return c;
}

void expectFree(const CollisionMap& map, const std::vector<Eigen::Vector4d>& path) {
  ASSERT_GE(path.size(), 2u);
  for (size_t i = 1; i < path.size(); ++i) {
    const Eigen::Vector3d a = path[i - 1].head<3>(), b = path[i].head<3>();
    for (int s = 0; s <= 20; ++s) {
      const Eigen::Vector3d p = a + (b - a) * (s / 20.0);
      ASSERT_GT(map.distance(p), 0.9) << "segment " << i << " at " << p.transpose();
    }
  }
}

const Eigen::Vector4d kUav(-4.0, -3.0, 2.5, 0.0);

// The first decision of a fresh explorer with `config` on `world`'s map, from kUav.
ExplorerDecision firstDecision(const ExplorerConfig& config, const WallWorld& world, const Frontier& f) {
  Explorer explorer(config, pathConfig());
  EXPECT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  return explorer.update(f, kUav, false);
}

// Two clusters of two ISEs: a near one on the UAV's side of the WallWorld
// wall and a far one behind it.
Frontier nearAndBehindTheWall() {
  return makeFrontier({{{-3, 2, 2.5}, {-3, 3, 2.5}}, {{4, -3, 2.5}, {4, -4, 2.5}}});
}

// Once an ISE of C_ins was seen, a frontier whose ISEs are all in C_rem ends
// the mission at once.
TEST(Explorer, CompleteFrontierEndsTheMission) {
  WallWorld world(true);
  Explorer explorer(ExplorerConfig(), pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  ASSERT_EQ(explorer.update(makeFrontier({{Eigen::Vector3d(-2.0, -3.0, 2.5)}}), kUav, false).action,
            ExplorerAction::kFly);
  Frontier f;
  Ise rem;
  rem.remaining = true;
  f.ises.push_back(rem);
  f.remaining = 1;
  const ExplorerDecision d = explorer.update(f, kUav, false);
  EXPECT_EQ(d.action, ExplorerAction::kDone);
  EXPECT_EQ(d.reason, ReplanReason::kComplete);
  EXPECT_NE(d.message.find("1 in C_rem"), std::string::npos) << d.message;
}

TEST(Explorer, EmptyFirstFrontiersHoverBeforeTheyEndTheMission) {
  WallWorld world(true);
  ExplorerConfig config;
  config.empty_updates_before_done = 3;
  Explorer explorer(config, pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  // A map that has seen nothing: no ISE at all is not a finished mission.
  EXPECT_EQ(explorer.update(Frontier(), kUav, false).action, ExplorerAction::kHover);
  EXPECT_EQ(explorer.update(Frontier(), kUav, false).action, ExplorerAction::kHover);
  EXPECT_EQ(explorer.update(Frontier(), kUav, false).action, ExplorerAction::kDone);
  // First frames whose ISEs all wait in C_rem (no free space known around
  // them yet; a CI run under load ended the faults rostest this way at 0 m)
  // hover the same way, then an ISE of C_ins lets the mission fly.
  Frontier only_rem;
  Ise rem;
  rem.remaining = true;
  only_rem.ises.assign(5, rem);
  only_rem.remaining = 5;
  Explorer waiting(config, pathConfig());
  ASSERT_TRUE(waiting.setMap(&world.collision(), world.bounds()).ok());
  const ExplorerDecision held = waiting.update(only_rem, kUav, false);
  EXPECT_EQ(held.action, ExplorerAction::kHover);
  EXPECT_NE(held.message.find("5 ISE(s) in C_rem"), std::string::npos) << held.message;
  EXPECT_EQ(waiting.update(only_rem, kUav, false).action, ExplorerAction::kHover);
  EXPECT_EQ(waiting.update(makeFrontier({{Eigen::Vector3d(-2.0, -3.0, 2.5)}}), kUav, false).action,
            ExplorerAction::kFly);
  // Once an ISE was seen, an empty frontier is complete at once.
  Explorer seen(config, pathConfig());
  ASSERT_TRUE(seen.setMap(&world.collision(), world.bounds()).ok());
  const ExplorerDecision first = seen.update(makeFrontier({{Eigen::Vector3d(-2.0, -3.0, 2.5)}}), kUav, false);
  EXPECT_EQ(first.action, ExplorerAction::kFly);
  EXPECT_EQ(seen.update(Frontier(), kUav, false).action, ExplorerAction::kDone);
}

// A hold cancels the leg being flown: after legCancelled() the same frontier
// gives a new leg to the same target, where it would otherwise say kContinue.
TEST(Explorer, CancelledLegIsPlannedAgainToTheSameTarget) {
  WallWorld world(true);
  Explorer explorer(ExplorerConfig(), pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  const Frontier f = nearAndBehindTheWall();
  const ExplorerDecision first = explorer.update(f, kUav, false);
  ASSERT_EQ(first.action, ExplorerAction::kFly) << first.message;
  const Eigen::Vector4d target = explorer.tour().front();
  const Eigen::Vector4d held(-3.8, -2.5, 2.5, 0.3);  // where the hold left the UAV, short of the target
  EXPECT_EQ(explorer.update(f, held, false).action, ExplorerAction::kContinue);
  explorer.legCancelled();
  EXPECT_FALSE(explorer.hasTarget());
  const ExplorerDecision again = explorer.update(f, held, false);
  ASSERT_EQ(again.action, ExplorerAction::kFly) << again.message;
  EXPECT_EQ(explorer.tour().front(), target);
  EXPECT_EQ(again.path.back().head<3>(), target.head<3>());
  EXPECT_EQ(explorer.stats().leg_failures, 0u);
}

TEST(Explorer, FirstFrontierPlansTheTourAndAFreeLegToItsFirstViewpoint) {
  WallWorld world(true);
  Explorer explorer(ExplorerConfig(), pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  const Frontier f = nearAndBehindTheWall();
  const ExplorerDecision d = explorer.update(f, kUav, false);
  ASSERT_EQ(d.action, ExplorerAction::kFly) << d.message;
  EXPECT_EQ(d.reason, ReplanReason::kInitial);
  EXPECT_TRUE(d.full_recompute);
  EXPECT_EQ(explorer.tour().size(), 4u);
  // The nearer cluster comes first (eq. 5 discounts distance).
  EXPECT_NEAR(d.target.x(), -3.0, 1e-9);
  EXPECT_NEAR((d.path.front().head<3>() - kUav.head<3>()).norm(), 0.0, 1e-9);
  EXPECT_NEAR((d.path.back() - d.target).norm(), 0.0, 1e-6);
  expectFree(world.collision(), d.path);
  EXPECT_EQ(explorer.stats().full_recomputes, 1u);
  // The tour's cluster-graph arcs: UAV -> first cluster, then cluster to cluster.
  ASSERT_EQ(explorer.tourArcs().size(), 2u);
  EXPECT_NEAR((explorer.tourArcs()[0].from - kUav.head<3>()).norm(), 0.0, 1e-9);
  for (const TourArc& arc : explorer.tourArcs()) EXPECT_GT(arc.utility, 0.0);
  // The roadmap the legs came from, as segments inside the bounds.
  const auto edges = explorer.pathPlanner().roadmapEdges(100);
  ASSERT_FALSE(edges.empty());
  EXPECT_LE(edges.size(), 100u);
  for (const auto& [a, b] : edges) EXPECT_TRUE(world.bounds().contains(a) && world.bounds().contains(b));
}

TEST(Explorer, LocalUpdateDropsCoveredViewpointsAndInsertsNewOnes) {
  WallWorld world(true);
  Explorer explorer(ExplorerConfig(), pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  const ExplorerDecision first =
      explorer.update(makeFrontier({{{-3, 2, 2.5}, {-3, 3, 2.5}}, {{4, -3, 2.5}}}), kUav, false);
  ASSERT_EQ(first.action, ExplorerAction::kFly);
  const Eigen::Vector4d target = first.target;
  // The far cluster was covered; a new viewpoint appeared next to the UAV's way.
  const Frontier second = makeFrontier({{{-3, 2, 2.5}, {-3, 3, 2.5}}, {{-2, 4, 2.5}}});
  const ExplorerDecision d = explorer.update(second, kUav, false);
  EXPECT_EQ(d.action, ExplorerAction::kContinue) << toString(d.action) << " " << d.message;
  EXPECT_EQ(d.reason, ReplanReason::kNewIses);
  EXPECT_FALSE(d.full_recompute);
  EXPECT_EQ(explorer.stats().local_updates, 1u);
  EXPECT_EQ(explorer.stats().full_recomputes, 1u);
  ASSERT_EQ(explorer.tour().size(), 3u);
  EXPECT_EQ(explorer.tour().front(), target);  // the current target stays first
  for (const Eigen::Vector4d& q : explorer.tour()) EXPECT_LT(q.x(), 0.0) << "covered viewpoint kept";
}

TEST(Explorer, CoveredTargetGivesALegToTheNextViewpoint) {
  WallWorld world(true);
  Explorer explorer(ExplorerConfig(), pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  const ExplorerDecision first = explorer.update(makeFrontier({{{-3, 2, 2.5}}, {{-3, -4.5, 2.5}}}), kUav, false);
  ASSERT_EQ(first.action, ExplorerAction::kFly);
  const Eigen::Vector3d covered = first.target.head<3>();
  const Eigen::Vector3d other = covered.y() > 0 ? Eigen::Vector3d(-3, -4.5, 2.5) : Eigen::Vector3d(-3, 2, 2.5);
  const ExplorerDecision d = explorer.update(makeFrontier({{other}}), kUav, false);
  ASSERT_EQ(d.action, ExplorerAction::kFly);
  EXPECT_EQ(d.reason, ReplanReason::kTargetCovered);
  EXPECT_NEAR((d.target.head<3>() - other).norm(), 0.0, 1e-9);
  EXPECT_EQ(explorer.stats().targets_covered, 1u);
}

TEST(Explorer, ReachedTargetsAdvanceAndRevisitsAreBlacklisted) {
  WallWorld world(true);
  ExplorerConfig config;
  config.max_visits = 2;
  Explorer explorer(config, pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  const Frontier f = makeFrontier({{{-3, 2, 2.5}}});
  ExplorerDecision d = explorer.update(f, kUav, false);
  ASSERT_EQ(d.action, ExplorerAction::kFly);
  // Arrive; the frontier still offers the same viewpoint (its ISE was not seen).
  d = explorer.update(f, d.target, true);
  EXPECT_EQ(explorer.stats().targets_reached, 1u);
  EXPECT_EQ(d.reason, ReplanReason::kTourFinished);  // its only viewpoint was visited: full recomputation
  ASSERT_EQ(d.action, ExplorerAction::kFly);
  d = explorer.update(f, d.target, true);
  EXPECT_EQ(explorer.stats().targets_reached, 2u);
  ASSERT_EQ(explorer.blacklist().size(), 1u);
  // Its ISE joins C_rem (nothing completes it from there): the mission is complete.
  EXPECT_EQ(d.action, ExplorerAction::kDone);
  EXPECT_EQ(d.reason, ReplanReason::kComplete);
  EXPECT_NE(d.message.find("1 more at 1 blacklisted place(s)"), std::string::npos) << d.message;
}

TEST(Explorer, UnreachableViewpointIsBlacklistedAfterMaxFailures) {
  WallWorld world(false);  // the wall is closed: the other side cannot be reached
  ExplorerConfig config;
  config.max_failures = 2;
  PathPlannerConfig path = pathConfig();
  path.iteration_budget = 300;
  Explorer explorer(config, path);
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  const Frontier f = makeFrontier({{{4, -3, 2.5}}});
  ExplorerDecision d = explorer.update(f, kUav, false);
  size_t updates = 1;
  while (d.action != ExplorerAction::kDone && updates < 10) {
    EXPECT_NE(d.action, ExplorerAction::kFly);
    d = explorer.update(f, kUav, false);
    ++updates;
  }
  EXPECT_EQ(d.action, ExplorerAction::kDone);
  EXPECT_EQ(d.reason, ReplanReason::kComplete);
  EXPECT_NE(d.message.find("blacklisted"), std::string::npos) << d.message;
  EXPECT_LE(updates, 3u) << "retried too long";
  ASSERT_EQ(explorer.blacklist().size(), 1u);
  EXPECT_NEAR((explorer.blacklist()[0] - Eigen::Vector3d(4, -3, 2.5)).norm(), 0.0, 1e-9);
  EXPECT_EQ(explorer.stats().leg_failures, 2u);
}

// Behind a closed wall every attempt would spend the planner's whole 10 s
// budget, six of them per decision; leg_time_budget stops the decision after
// the first, cut to 0.3 s, and it hovers. The next decision goes on down the
// tour with a budget of its own.
TEST(Explorer, LegTimeBudgetEndsTheAttemptsOfADecision) {
  WallWorld world(false);
  ExplorerConfig config;
  config.leg_time_budget = 0.3;
  PathPlannerConfig path = pathConfig();
  path.iteration_budget = 0;  // bounded by time only: 10 s per attempt
  Explorer explorer(config, path);
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  const Frontier f = makeFrontier({{{4, -3, 2.5}}, {{4, 3, 2.5}}, {{3, -4, 2.5}}, {{3, 4, 2.5}}});
  for (size_t decision = 1; decision <= 2; ++decision) {
    const ExplorerDecision d = explorer.update(f, kUav, false);
    EXPECT_EQ(d.action, ExplorerAction::kHover) << d.message;
    EXPECT_NE(d.message.find("leg_time_budget"), std::string::npos) << d.message;
    EXPECT_EQ(explorer.stats().budget_stops, decision);
    EXPECT_EQ(explorer.stats().leg_failures, decision) << "one cut attempt per decision";
    EXPECT_EQ(d.path_status, PathStatus::kTimeout);
    EXPECT_LT(d.timings.path_ms, 5000.0) << "an uncapped decision takes 60 s";
  }
}

TEST(Explorer, ObstacleOnTheLegGivesANewFreeLeg) {
  WallWorld world(true);
  Explorer explorer(ExplorerConfig(), pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  const Eigen::Vector4d uav(-4.0, 3.0, 2.5, 0.0);
  const ExplorerDecision first = explorer.update(makeFrontier({{{4.5, 0, 2.5}}}), uav, false);
  ASSERT_EQ(first.action, ExplorerAction::kFly);
  EXPECT_EQ(explorer.checkPath(uav).action, ExplorerAction::kContinue);
  // A pillar appears on the leg, in the open beyond the wall.
  Eigen::Vector3d on_leg = Eigen::Vector3d::Constant(NAN);
  for (size_t i = 1; i < first.path.size() && !on_leg.allFinite(); ++i)
    for (int s = 0; s <= 50; ++s) {
      const Eigen::Vector3d p = first.path[i - 1].head<3>() + (first.path[i] - first.path[i - 1]).head<3>() * (s / 50.0);
      if (p.x() >= 1.8 && p.x() <= 2.6) {
        on_leg = p;
        break;
      }
    }
  ASSERT_TRUE(on_leg.allFinite());
  world.addBox(Eigen::Vector3d(on_leg.x() - 0.4, on_leg.y() - 0.4, 0.0),
               Eigen::Vector3d(on_leg.x() + 0.4, on_leg.y() + 0.4, 5.0));
  explorer.mapChanged();
  const ExplorerDecision d = explorer.checkPath(uav);
  ASSERT_EQ(d.action, ExplorerAction::kFly) << d.message;
  EXPECT_EQ(d.reason, ReplanReason::kPathBlocked);
  expectFree(world.collision(), d.path);
  EXPECT_EQ(explorer.stats().paths_blocked, 1u);
}

TEST(Explorer, SameInputsGiveTheSamePlan) {
  auto plan = [] {
    WallWorld world(true);
    Explorer explorer(ExplorerConfig(), pathConfig());
    EXPECT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
    return explorer.update(makeFrontier({{{-3, 2, 2.5}, {-3, 3, 2.5}}, {{4, -3, 2.5}}, {{4, 4, 2.5}}}), kUav, false);
  };
  const ExplorerDecision a = plan(), b = plan();
  ASSERT_EQ(a.path.size(), b.path.size());
  for (size_t i = 0; i < a.path.size(); ++i) EXPECT_EQ(a.path[i], b.path[i]);
}

TEST(Explorer, ClustersWithoutGainLeaveNothingReachable) {
  WallWorld world(true);
  Explorer explorer(ExplorerConfig(), pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  Frontier f = makeFrontier({{{-3, 2, 2.5}}});
  f.clusters[0].gain = 0.0;
  const ExplorerDecision d = explorer.update(f, kUav, false);
  EXPECT_EQ(d.action, ExplorerAction::kDone);
  EXPECT_EQ(d.reason, ReplanReason::kNoReachableTarget);
  EXPECT_NE(d.message.find("1 ISE(s) of C_ins remain"), std::string::npos) << d.message;
}

// travel_yaw: every vertex but the last looks along its outgoing segment, the
// last one has the target's yaw, reached over the final turn_distance metres.
TEST(Explorer, TravelYawLooksAlongTheLegAndTurnsToTheTargetAtTheEnd) {
  WallWorld world(true);
  ExplorerConfig config;
  config.travel_yaw = true;
  config.turn_distance = 1.5;
  Explorer explorer(config, pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  Frontier f = makeFrontier({{{4.5, 0, 2.5}}});
  f.viewpoints[0].yaw = 2.0;
  const ExplorerDecision d = explorer.update(f, kUav, false);
  ASSERT_EQ(d.action, ExplorerAction::kFly) << d.message;
  ASSERT_GE(d.path.size(), 3u);
  EXPECT_NEAR(d.path.back().w(), 2.0, 1e-9);
  EXPECT_NEAR((d.path.back() - d.target).norm(), 0.0, 1e-6);
  for (size_t i = 0; i + 1 < d.path.size(); ++i) {
    const Eigen::Vector2d step = (d.path[i + 1] - d.path[i]).head<2>();
    if (step.norm() < 0.2) continue;
    EXPECT_NEAR(d.path[i].w(), std::atan2(step.y(), step.x()), 1e-9) << "vertex " << i;
  }
  const size_t n = d.path.size();
  EXPECT_NEAR((d.path[n - 1] - d.path[n - 2]).head<3>().norm(), 1.5, 1e-6);
  expectFree(world.collision(), d.path);

  // Without it the yaw goes from the UAV's to the target's along the leg.
  Explorer plain(ExplorerConfig(), pathConfig());
  ASSERT_TRUE(plain.setMap(&world.collision(), world.bounds()).ok());
  const ExplorerDecision p = plain.update(f, kUav, false);
  ASSERT_EQ(p.action, ExplorerAction::kFly);
  EXPECT_NEAR(p.path.front().w(), kUav.w(), 1e-9);
  EXPECT_NEAR(p.path.back().w(), 2.0, 1e-9);
}

// min_visible: a viewpoint whose C_q is empty leaves the tour; when nothing
// else is left the filter is lifted rather than ending the mission.
TEST(Explorer, ViewpointsThatSeeNothingAreLeftOutOfTheTour) {
  WallWorld world(true);
  ExplorerConfig config;
  config.min_visible = 1;
  Explorer explorer(config, pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  Frontier f = makeFrontier({{{-3, 2, 2.5}, {-3, 3, 2.5}}});
  f.viewpoints[1].visible.clear();
  ExplorerDecision d = explorer.update(f, kUav, false);
  ASSERT_EQ(d.action, ExplorerAction::kFly);
  ASSERT_EQ(explorer.tour().size(), 1u);
  EXPECT_NEAR((explorer.tour()[0].head<3>() - Eigen::Vector3d(-3, 2, 2.5)).norm(), 0.0, 1e-9);
  EXPECT_EQ(explorer.stats().dropped_no_gain, 1u);
  Explorer only(config, pathConfig());
  ASSERT_TRUE(only.setMap(&world.collision(), world.bounds()).ok());
  Frontier g = makeFrontier({{{-3, 2, 2.5}}});
  g.viewpoints[0].visible.clear();
  d = only.update(g, kUav, false);
  EXPECT_EQ(d.action, ExplorerAction::kFly) << d.message;
}

TEST(Explorer, ViewpointsFacingLittleUnknownWaitUntilTheTourRunsOut) {
  WallWorld world(true);
  // The near viewpoint faces almost nothing unseen, the far one a lot.
  Frontier f = makeFrontier({{{-3, -2, 2.5}}, {{-3, 3, 2.5}}});
  f.viewpoints[0].unknown_fraction = 0.01;
  f.viewpoints[1].unknown_fraction = 0.5;
  const ExplorerDecision near = firstDecision(ExplorerConfig(), world, f);
  ASSERT_EQ(near.action, ExplorerAction::kFly);
  EXPECT_NEAR((near.target.head<3>() - Eigen::Vector3d(-3, -2, 2.5)).norm(), 0.0, 1e-9);

  ExplorerConfig config;
  config.pool_unknown_below = 0.05;
  Explorer explorer(config, pathConfig());
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  ExplorerDecision d = explorer.update(f, kUav, false);
  ASSERT_EQ(d.action, ExplorerAction::kFly);
  EXPECT_NEAR((d.target.head<3>() - Eigen::Vector3d(-3, 3, 2.5)).norm(), 0.0, 1e-9);
  EXPECT_EQ(explorer.tour().size(), 1u);
  EXPECT_EQ(explorer.stats().pooled, 1u);
  // A new leftover does not join the tour while the target is still open.
  Frontier g = makeFrontier({{{-3, -2, 2.5}, {-2, -3.5, 2.5}}, {{-3, 3, 2.5}}});
  g.viewpoints[0].unknown_fraction = g.viewpoints[1].unknown_fraction = 0.01;
  g.viewpoints[2].unknown_fraction = 0.5;
  d = explorer.update(g, kUav, false);
  EXPECT_EQ(d.action, ExplorerAction::kContinue);
  EXPECT_EQ(explorer.tour().size(), 1u);
  // Once the far one is covered the tour runs out: the leftovers are next,
  // in the tour's order (the nearer first), none pooled again, none promoted
  // for the larger sliver of unknown space the farther one faces.
  Frontier h = makeFrontier({{{-3, -2, 2.5}, {-2, -3.5, 2.5}}});
  h.viewpoints[0].unknown_fraction = 0.001;
  h.viewpoints[1].unknown_fraction = 0.04;
  for (const bool ranked : {false, true}) {
    ExplorerConfig end_config = config;
    end_config.head_lookahead = ranked ? 1000 : 0;
    end_config.head_unknown = ranked;
    Explorer end(end_config, pathConfig());
    ASSERT_TRUE(end.setMap(&world.collision(), world.bounds()).ok());
    ASSERT_EQ(end.update(f, kUav, false).action, ExplorerAction::kFly);
    ASSERT_EQ(end.update(g, kUav, false).action, ExplorerAction::kContinue);
    const size_t pooled = end.stats().pooled;
    d = end.update(h, kUav, false);
    ASSERT_EQ(d.action, ExplorerAction::kFly) << d.message;
    EXPECT_NEAR((d.target.head<3>() - Eigen::Vector3d(-3, -2, 2.5)).norm(), 0.0, 1e-9) << ranked;
    EXPECT_EQ(end.tour().size(), 2u);
    EXPECT_EQ(end.stats().pooled, pooled);
    EXPECT_EQ(end.stats().promoted, 0u);
    EXPECT_EQ(end.stats().full_recomputes, 2u);
  }
}

// head_lookahead: of the first tour viewpoints, the one with the best
// |C_q| exp(-lambda_tc d) is flown first.
TEST(Explorer, HeadLookaheadFliesTheBestOfTheFirstViewpointsFirst) {
  WallWorld world(true);
  // Near viewpoint seeing 1 ISE, farther one (same side of the wall) seeing 20.
  Frontier f = makeFrontier({{{-3, -1.5, 2.5}}, {{-3, 3, 2.5}}});
  for (int i = 0; i < 19; ++i) {
    Ise ise;
    ise.position = Eigen::Vector3d(-2, 3, 2.5);
    ise.viewpoint = 1;
    f.viewpoints[1].visible.push_back(static_cast<uint32_t>(f.ises.size()));
    f.ises.push_back(ise);
  }
  auto firstTarget = [&](int lookahead, size_t* promoted, Explorer::HeadGain gain = {}, bool unknown = false) {
    ExplorerConfig config;
    config.head_lookahead = lookahead;
    config.head_unknown = unknown;
    Explorer explorer(config, pathConfig());
    explorer.setHeadGain(gain);
    EXPECT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
    const ExplorerDecision d = explorer.update(f, kUav, false);
    EXPECT_EQ(d.action, ExplorerAction::kFly) << d.message;
    EXPECT_EQ(explorer.tour().size(), 2u) << "nothing leaves the tour";
    *promoted = explorer.stats().promoted;
    return d.target;
  };
  size_t promoted = 0;
  // The tour (shortest open path) starts at the near one: 1 * e^(-0.3 * 1.8) = 0.58
  // against 20 * e^(-0.3 * 6.1) = 3.2 for the far one.
  EXPECT_NEAR(firstTarget(0, &promoted).y(), -1.5, 1e-9);
  EXPECT_EQ(promoted, 0u);
  EXPECT_NEAR(firstTarget(2, &promoted).y(), 3.0, 1e-9);
  EXPECT_EQ(promoted, 1u);
  // A head gain (nbv_mission --oracle-gain) ranks instead of |C_q|: 10 for the
  // near one, 1 for the far one, so the near one stays first.
  const Explorer::HeadGain near_more = [](const Eigen::Vector4d& q) { return q.y() < 0.0 ? 10.0 : 1.0; };
  EXPECT_NEAR(firstTarget(2, &promoted, near_more).y(), -1.5, 1e-9);
  EXPECT_EQ(promoted, 0u);
  // head_unknown weighs |C_q| by the share of view rays meeting unknown
  // space: the far one looks at little (20 * 0.05 * 0.16 = 0.16 against 0.58).
  f.viewpoints[1].unknown_fraction = 0.05;
  EXPECT_NEAR(firstTarget(2, &promoted, {}, true).y(), -1.5, 1e-9);
  EXPECT_EQ(promoted, 0u);
  EXPECT_NEAR(firstTarget(2, &promoted, {}, false).y(), 3.0, 1e-9);
  EXPECT_EQ(promoted, 1u);
}

// head_vertical_scale: a climb counts s times its height in the comparison.
TEST(Explorer, HeadVerticalScaleMakesAClimbCostMoreThanAMoveAcross) {
  WallWorld world(true);
  // 1.2 m above the UAV, and 2 m beside it at its height: one ISE each.
  const Frontier f = makeFrontier({{{-4, -3, 3.7}}, {{-4, -1, 2.5}}});
  auto firstTarget = [&](double scale) {
    ExplorerConfig config;
    config.head_lookahead = 2;
    config.head_vertical_scale = scale;
    const ExplorerDecision d = firstDecision(config, world, f);
    EXPECT_EQ(d.action, ExplorerAction::kFly) << d.message;
    return d.target;
  };
  EXPECT_NEAR(firstTarget(1.0).z(), 3.7, 1e-9);  // 1.2 m against 2 m
  EXPECT_NEAR(firstTarget(2.0).z(), 2.5, 1e-9);  // 2.4 m against 2 m
}

TEST(Explorer, ConfigRefusesBadValues) {
  ExplorerConfig c;
  EXPECT_TRUE(c.validate().ok());
  c.max_failures = 0;
  EXPECT_NE(c.validate().message().find("max_failures"), std::string::npos);
  c = ExplorerConfig();
  c.match_radius = std::nan("");
  EXPECT_NE(c.validate().message().find("match_radius"), std::string::npos);
  c = ExplorerConfig();
  c.turn_distance = -1.0;
  EXPECT_NE(c.validate().message().find("turn_distance"), std::string::npos);
  c = ExplorerConfig();
  c.min_visible = -1;
  EXPECT_NE(c.validate().message().find("min_visible"), std::string::npos);
  c = ExplorerConfig();
  c.pool_unknown_below = 1.5;
  EXPECT_NE(c.validate().message().find("pool_unknown_below"), std::string::npos);
  c = ExplorerConfig();
  c.head_lookahead = -1;
  EXPECT_NE(c.validate().message().find("head_lookahead"), std::string::npos);
  c = ExplorerConfig();
  c.head_vertical_scale = -0.5;
  EXPECT_NE(c.validate().message().find("head_vertical_scale"), std::string::npos);
  for (double budget : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    c = ExplorerConfig();
    c.leg_time_budget = budget;
    EXPECT_NE(c.validate().message().find("leg_time_budget"), std::string::npos) << budget;
  }
}

// corridor_guide: with check_reachable, the first leg to a target behind the
// wall follows the reachable space's corridor (the roadmap is empty, so the
// guide answers before any growth), free of the wall; without it the same
// leg comes from the roadmap.
TEST(Explorer, CorridorGuideGivesTheLegBehindTheWall) {
  WallWorld world(true);
  const Frontier f = makeFrontier({{{4, -3, 2.5}, {4, -4, 2.5}}});
  for (const bool guide : {false, true}) {
    ExplorerConfig config;
    config.check_reachable = true;
    config.corridor_guide = guide;
    PathPlannerConfig path = pathConfig();
    path.lattice_step = 0.3;
    Explorer explorer(config, path);
    ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
    const ExplorerDecision d = explorer.update(f, kUav, false);
    ASSERT_EQ(d.action, ExplorerAction::kFly) << d.message;
    expectFree(world.collision(), d.path);
    EXPECT_EQ(explorer.stats().corridor_legs, guide ? 1u : 0u) << guide;
    if (guide) {
      EXPECT_EQ(explorer.stats().roadmap_growths, 0u);
    }
  }
}

}  // namespace
