#include "surface_nbv/tracking/tracker_sim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <limits>

using namespace surface_nbv;

namespace {

struct RunStats {
  double max_error = 0.0;           // |p - p_ref(t)| over the whole run, m
  double steady_error = 0.0;        // the same in [settle, until] (past the start from rest, before the stop)
  double max_yaw_error = 0.0;       // rad, after `settle`
  double max_command_change = 0.0;  // max |a_k - a_k-1| over one step after `settle`, m/s^2
  double final_error = 0.0;
};

// Steps until `end`, checking the limits at every step. The reference starts
// at 0.5 m/s from rest, which no UAV follows exactly (a lag of at least
// v^2 / 2 a_max = 8 cm) and stops dead at the end, so errors are also
// measured between `settle` and `until`.
RunStats run(TrackerSim* sim, double end, double settle = -1e9, double until = 1e9) {
  RunStats stats;
  const TrackerSimConfig& c = sim->config();
  UavCommand previous = sim->command();
  while (sim->time() < end) {
    sim->step();
    const UavState& s = sim->state();
    const UavCommand& u = sim->command();
    EXPECT_TRUE(s.allFinite() && u.a_W.allFinite() && std::isfinite(u.yaw_rate));
    EXPECT_LE(s.v_W.cwiseAbs().maxCoeff(), c.model.v_max + 1e-12);
    EXPECT_LE(u.a_W.cwiseAbs().maxCoeff(), c.model.a_max);
    EXPECT_LE(std::abs(u.yaw_rate), c.model.yaw_rate_max);
    if (::testing::Test::HasFailure()) break;
    const TrajectorySample ref = sim->reference();
    const double error = (s.p_W - ref.p_W).norm();
    stats.max_error = std::max(stats.max_error, error);
    stats.final_error = error;
    if (sim->time() >= settle && sim->time() <= until) {
      stats.steady_error = std::max(stats.steady_error, error);
      stats.max_yaw_error = std::max(stats.max_yaw_error, std::abs(wrapAngle(s.yaw - ref.yaw)));
      stats.max_command_change = std::max(stats.max_command_change, (u.a_W - previous.a_W).cwiseAbs().maxCoeff());
    }
    previous = u;
  }
  ::testing::Test::RecordProperty("max_error_m", std::to_string(stats.max_error));
  ::testing::Test::RecordProperty("steady_error_m", std::to_string(stats.steady_error));
  ::testing::Test::RecordProperty("max_yaw_error_rad", std::to_string(stats.max_yaw_error));
  return stats;
}

UavState at(const Eigen::Vector3d& p, double yaw = 0.0) {
  UavState s;
  s.p_W = p;
  s.yaw = yaw;
  return s;
}

std::vector<Waypoint> polyline(std::initializer_list<Eigen::Vector4d> points) {
  std::vector<Waypoint> w;
  for (const Eigen::Vector4d& q : points) w.push_back({q.head<3>(), q[3]});
  return w;
}

}  // namespace

TEST(TrackerSim, ConfigNamesBadKey) {
  EXPECT_TRUE(TrackerSimConfig().validate());
  TrackerSimConfig c;
  c.control_period = 0.015;
  EXPECT_NE(c.validate().message().find("control_period"), std::string::npos);
  c = TrackerSimConfig();
  c.mpc.jerk_max = 0;
  EXPECT_NE(c.validate().message().find("mpc: jerk_max"), std::string::npos);
  c = TrackerSimConfig();
  c.model.a_max = 0;
  EXPECT_NE(c.validate().message().find("model: a_max"), std::string::npos);
}

// Achieved bounds (default config: N = 20, dt = 0.1 s, MPC every 0.1 s, sim
// step 0.01 s), error to the timed reference at the same time:
//   line    start 14.4 cm, cruise 0.2 mm, at rest at the end 0.0 mm
//   corner  8.0 cm through the 90 degree corner, yaw 0.01 rad
//   circle  cruise 1.8 mm (r = 2 m), yaw < 0.01 rad
// The start bound is physics: a reference leaving at 0.5 m/s from rest is
// followed with a lag of at least v^2 / (2 a_max) = 8.3 cm, more with the jerk limit.
constexpr double kStartBound = 0.15;

// Straight line, 10 m at 0.5 m/s from rest: cruise within 1 mm.
TEST(TrackerSim, StraightLineCruiseWithin1mm) {
  TrackerSim sim(TrackerSimConfig(), at(Eigen::Vector3d(0, 0, 2)));
  const Trajectory line = timeWaypoints(polyline({{0, 0, 2, 0}, {10, 0, 2, 0}}), sim.time());
  ASSERT_TRUE(sim.setTrajectory(line));
  EXPECT_EQ(sim.mode(), TrackerMode::kTracking);
  const RunStats stats = run(&sim, line.endTime() + 5.0, 3.0, line.endTime() - 2.0);
  EXPECT_LT(stats.max_error, kStartBound);
  EXPECT_LT(stats.steady_error, 1e-3);
  EXPECT_LT(stats.final_error, 1e-3);
  EXPECT_EQ(sim.mode(), TrackerMode::kFinished);
}

// A 90 degree corner (5 m, 5 m) at 0.5 m/s with a quarter yaw turn: within
// 9 cm through the corner (the reference turns instantly), yaw within 0.02 rad.
TEST(TrackerSim, CornerWithin9cm) {
  TrackerSim sim(TrackerSimConfig(), at(Eigen::Vector3d(0, 0, 2)));
  const Trajectory corner =
      timeWaypoints(polyline({{0, 0, 2, 0}, {5, 0, 2, 0}, {5, 5, 2, M_PI / 2}}), sim.time());
  ASSERT_TRUE(sim.setTrajectory(corner));
  const RunStats stats = run(&sim, corner.endTime() + 5.0, 3.0, corner.endTime() - 2.0);
  EXPECT_LT(stats.max_error, kStartBound);
  EXPECT_LT(stats.steady_error, 0.09);
  EXPECT_GT(stats.steady_error, 0.01);  // the corner is really cut: the measure works
  EXPECT_LT(stats.max_yaw_error, 0.02);
  EXPECT_LT(stats.final_error, 1e-3);
}

// A circle of radius 2 m at 0.5 m/s (points every 5 degrees), facing the
// centre, one lap: cruise within 5 mm, yaw within 0.01 rad.
TEST(TrackerSim, CircleCruiseWithin5mm) {
  std::vector<Waypoint> w;
  for (int i = 0; i <= 72; ++i) {
    const double a = i * M_PI / 36;
    w.push_back({Eigen::Vector3d(2 * std::cos(a), 2 * std::sin(a), 3), wrapAngle(a + M_PI)});
  }
  TrackerSim sim(TrackerSimConfig(), at(w.front().p_W, w.front().yaw));
  const Trajectory circle = timeWaypoints(w, sim.time(), 0.5, 1.0);
  ASSERT_TRUE(sim.setTrajectory(circle));
  EXPECT_NEAR(circle.endTime(), 72 * 2 * 2 * std::sin(M_PI / 72) / 0.5, 1e-9);
  const RunStats stats = run(&sim, circle.endTime() + 5.0, 3.0, circle.endTime() - 2.0);
  EXPECT_LT(stats.max_error, kStartBound);
  EXPECT_LT(stats.steady_error, 5e-3);
  EXPECT_LT(stats.max_yaw_error, 0.01);
}

TEST(TrackerSim, RefusedTrajectoriesHoldThePose) {
  const Eigen::Vector3d start(1, 2, 3);
  TrackerSim sim(TrackerSimConfig(), at(start));
  TrajectoryPoint a, b;
  a.p_W = start;
  b.p_W = start + Eigen::Vector3d(1, 0, 0);
  b.t = 2.0;
  // Fly half way along a valid line, then send bad ones: each is refused and
  // the UAV stops and holds where it was when the bad one arrived.
  ASSERT_TRUE(sim.setTrajectory(Trajectory({a, b})));
  sim.runUntil(1.0);
  std::vector<Trajectory> bad;
  bad.push_back(Trajectory());
  TrajectoryPoint nan = b;
  nan.p_W.y() = std::numeric_limits<double>::quiet_NaN();
  bad.push_back(Trajectory({a, nan}));
  TrajectoryPoint early = b;
  early.t = -1.0;
  bad.push_back(Trajectory({a, early}));
  TrajectoryPoint far = a;
  far.p_W.x() += 30.0;
  bad.push_back(Trajectory({far, b}));
  for (const Trajectory& t : bad) {
    const Eigen::Vector3d held = sim.state().p_W;
    const Status s = sim.setTrajectory(t);
    EXPECT_FALSE(s);
    EXPECT_EQ(sim.lastRefusal(), s.message());
    EXPECT_EQ(sim.mode(), TrackerMode::kHolding);
    const RunStats stats = run(&sim, sim.time() + 5.0);
    EXPECT_LT((sim.state().p_W - held).norm(), 0.05) << s.message();
    EXPECT_LT(sim.state().v_W.norm(), 1e-3) << s.message();
    EXPECT_LT(stats.final_error, 1e-3);
  }
}

// Swapping to a new trajectory mid-flight (a right turn from rest where the
// UAV is, while it cruises at 0.5 m/s): the command changes by at most
// jerk_max * dt per control step, and the new one is tracked.
TEST(TrackerSim, SwapIsSmooth) {
  TrackerSim sim(TrackerSimConfig(), at(Eigen::Vector3d::Zero()));
  ASSERT_TRUE(sim.setTrajectory(timeWaypoints(polyline({{0, 0, 0, 0}, {20, 0, 0, 0}}), sim.time())));
  const RunStats cruise = run(&sim, 10.0, 3.0);
  const Eigen::Vector3d here = sim.state().p_W;
  ASSERT_TRUE(sim.setTrajectory(timeWaypoints(
      polyline({{here.x(), here.y(), here.z(), 0}, {here.x(), here.y() - 5, here.z(), 0}}), sim.time())));
  const RunStats swap = run(&sim, 25.0);
  const MpcConfig& mpc = sim.config().mpc;
  EXPECT_LT(cruise.max_command_change, 0.01);
  EXPECT_GT(swap.max_command_change, 0.1);  // the swap really demands a change
  EXPECT_LE(swap.max_command_change, mpc.jerk_max * mpc.dt + 1e-9);
  EXPECT_LT(swap.max_error, 0.25);
  EXPECT_LT(swap.final_error, 1e-3);
}

// Adversarial references that pass validation: a 100 m step in 0.1 s, yaw
// jumping by pi and by 1e4 rad between points, a NaN one refused mid-flight.
// The limits hold at every step (checked inside run()).
TEST(TrackerSim, LimitsHoldUnderAdversarialReferences) {
  TrackerSim sim(TrackerSimConfig(), at(Eigen::Vector3d::Zero()));
  std::vector<TrajectoryPoint> points(40);
  for (int i = 0; i < 40; ++i) {
    points[i].t = sim.time() + 0.1 * i;
    points[i].p_W = i == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(100, (i % 2) * 50.0, -30);
    points[i].yaw = i % 3 == 0 ? 1e4 : (i % 2 ? M_PI : -M_PI / 2);
    points[i].has_velocity = i % 5 == 0;
    points[i].v_W = Eigen::Vector3d(1e3, -1e3, 0);
  }
  ASSERT_TRUE(sim.setTrajectory(Trajectory(points)));
  run(&sim, 3.0);
  EXPECT_GT(sim.state().v_W.x(), 0.9);  // flying at the box towards the target
  points[5].p_W.z() = std::numeric_limits<double>::quiet_NaN();
  points[0].p_W = sim.state().p_W;
  EXPECT_FALSE(sim.setTrajectory(Trajectory(points)));
  run(&sim, 10.0);
  EXPECT_EQ(sim.mode(), TrackerMode::kHolding);
  EXPECT_LT(sim.state().v_W.norm(), 0.05);
}

TEST(TrackerSim, RunsRepeatExactly) {
  auto flight = [] {
    TrackerSim sim(TrackerSimConfig(), at(Eigen::Vector3d(0, 0, 1)));
    sim.setTrajectory(timeWaypoints(polyline({{0, 0, 1, 0}, {3, 1, 2, 1}, {0, 2, 1, -2}}), 0.0));
    sim.runUntil(20.0);
    return sim.state();
  };
  const UavState a = flight(), b = flight();
  EXPECT_EQ(a.p_W, b.p_W);
  EXPECT_EQ(a.v_W, b.v_W);
  EXPECT_EQ(a.yaw, b.yaw);
}
