// The mission's rules (planning/mission_supervisor.h): take-off spin, leg
// ends (tracker, settle, lookahead), decisions by period or new frontier,
// limits, the tally and its report keys.
#include "surface_nbv/planning/mission_supervisor.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace surface_nbv;

namespace {

SupervisorConfig headless(double period = 1.0) {
  SupervisorConfig c;
  c.frontier_period = period;
  return c;
}

SupervisorInput at(double t, const Eigen::Vector4d& uav = Eigen::Vector4d::Zero()) {
  SupervisorInput in;
  in.t = t;
  in.uav = uav;
  return in;
}

ExplorerDecision decision(ExplorerAction action, ReplanReason reason = ReplanReason::kNone, double ms = 1.0) {
  ExplorerDecision d;
  d.action = action;
  d.reason = reason;
  d.message = "test";
  d.timings.total_ms = ms;
  return d;
}

// Take-off without a spin, the first decision at once: a leg to (5, 0, 0) ending at 10 s.
void flyFirstLeg(MissionSupervisor* s) {
  s->takeOff(Eigen::Vector4d::Zero());
  ASSERT_EQ(s->poll(at(0.0)), SupervisorStep::kDecide);
  s->decided(decision(ExplorerAction::kFly), at(0.0));
  s->legSent(Eigen::Vector4d(5, 0, 0, 0), 10.0);
}

}  // namespace

TEST(MissionSupervisor, ValidatesTheFlightKeys) {
  MissionFlightConfig f;
  EXPECT_TRUE(f.validate().ok());
  f.speed = 0.0;
  EXPECT_NE(f.validate().message().find("speed"), std::string::npos);
  f = MissionFlightConfig();
  f.max_flight_time = -1.0;
  EXPECT_NE(f.validate().message().find("max_flight_time"), std::string::npos);
  f = MissionFlightConfig();
  f.start_spin = std::nan("");
  EXPECT_FALSE(f.validate().ok());
}

TEST(MissionSupervisor, SpinsInQuarterTurnsBeforeTheFirstDecision) {
  MissionSupervisor s(headless());
  const Eigen::Vector4d start(1.0, 2.0, 3.0, 0.5);
  const std::vector<Eigen::Vector4d> spin = s.takeOff(start);
  ASSERT_EQ(spin.size(), 5u);  // quarter turns at most: 6.2832 is a hair over 2 pi
  for (size_t k = 0; k < spin.size(); ++k) {
    EXPECT_EQ(spin[k].head<3>(), start.head<3>());
    EXPECT_NEAR(spin[k].w(), 0.5 + 6.2832 * (k + 1) / 5.0, 1e-12);
  }
  EXPECT_TRUE(s.spinning());
  s.legSent(spin.back(), 12.0);
  // The period is long past but the spin has not ended: no decision.
  EXPECT_EQ(s.poll(at(5.0)), SupervisorStep::kWait);
  SupervisorInput done = at(12.5);
  done.tracker_finished = true;
  EXPECT_EQ(s.poll(done), SupervisorStep::kDecide);
  EXPECT_FALSE(s.spinning());
  EXPECT_TRUE(s.legEndedAtPoll());
}

TEST(MissionSupervisor, WithoutASpinTheFirstPollDecides) {
  SupervisorConfig c = headless();
  c.flight.start_spin = 0.0;
  MissionSupervisor s(c);
  EXPECT_TRUE(s.takeOff(Eigen::Vector4d::Zero()).empty());
  EXPECT_FALSE(s.spinning());
  EXPECT_EQ(s.poll(at(0.0)), SupervisorStep::kDecide);
}

TEST(MissionSupervisor, DroppingTheSpinEndsItAndDecides) {
  SupervisorConfig c = headless(0.0);
  MissionSupervisor s(c);
  s.legSent(s.takeOff(Eigen::Vector4d::Zero()).back(), 12.0);
  EXPECT_EQ(s.poll(at(1.0)), SupervisorStep::kWait);
  s.legDropped();  // a hold (stale odometry) during the spin
  EXPECT_FALSE(s.spinning());
  EXPECT_EQ(s.poll(at(1.5)), SupervisorStep::kDecide);
  EXPECT_EQ(s.tally().legs_dropped, 1u);
}

TEST(MissionSupervisor, DecidesEveryPeriodAndAtOnceWhenALegToATargetEnds) {
  SupervisorConfig c = headless(1.0);
  c.flight.start_spin = 0.0;
  MissionSupervisor s(c);
  ASSERT_NO_FATAL_FAILURE(flyFirstLeg(&s));
  EXPECT_EQ(s.poll(at(0.5)), SupervisorStep::kWait);
  EXPECT_EQ(s.poll(at(0.999999)), SupervisorStep::kWait);
  EXPECT_EQ(s.poll(at(1.0)), SupervisorStep::kDecide);  // the period is due
  s.decided(decision(ExplorerAction::kContinue), at(1.0));
  SupervisorInput finished = at(1.3);
  finished.tracker_finished = true;
  EXPECT_EQ(s.poll(finished), SupervisorStep::kWait);  // ended, but no target to answer for
  finished.has_target = true;
  EXPECT_EQ(s.poll(finished), SupervisorStep::kDecide);
}

TEST(MissionSupervisor, LookaheadEndsALegAtItsGoalBeforeItsReferenceEnds) {
  SupervisorConfig c = headless(100.0);
  c.flight.leg_lookahead = 2.0;
  c.reach_tolerance = 1.0;
  MissionSupervisor s(c);
  const Eigen::Vector4d goal(5.0, 0.0, 2.0, 0.0);
  s.legSent(goal, 10.0);
  EXPECT_FALSE(s.legEnded(at(7.0, goal)));                          // 3 s left
  EXPECT_TRUE(s.legEnded(at(8.5, Eigen::Vector4d(5.5, 0, 2, 0.2))));  // 1.5 s left, at the goal
  EXPECT_FALSE(s.legEnded(at(8.5, Eigen::Vector4d(5.0, 0, 2, 0.5))));  // not facing its yaw
  EXPECT_FALSE(s.legEnded(at(8.5, Eigen::Vector4d(6.5, 0, 2, 0.0))));  // 1.5 m off
  EXPECT_TRUE(s.legEnded(at(8.5, Eigen::Vector4d(5.0, 0, 2, 2 * M_PI))));  // the same yaw, a turn later
  c.flight.leg_lookahead = 0.0;
  MissionSupervisor off(c);
  off.legSent(goal, 10.0);
  EXPECT_FALSE(off.legEnded(at(9.9, goal)));
}

TEST(MissionSupervisor, SettleEndsALegOnceAndNewFrontiersDecide) {
  SupervisorConfig c;  // as nbv_planner runs it
  c.frontier_period = 0.0;
  c.leg_settle = 0.5;
  c.flight.start_spin = 0.0;
  MissionSupervisor s(c);
  ASSERT_NO_FATAL_FAILURE(flyFirstLeg(&s));
  EXPECT_EQ(s.poll(at(3.0)), SupervisorStep::kWait);  // no new frontier, leg on
  SupervisorInput fresh = at(3.0);
  fresh.frontier_new = true;
  EXPECT_EQ(s.poll(fresh), SupervisorStep::kDecide);
  s.decided(decision(ExplorerAction::kContinue), fresh);
  EXPECT_FALSE(s.legEnded(at(10.4)));
  SupervisorInput settled = at(10.5);
  settled.has_target = true;
  EXPECT_TRUE(s.legEnded(settled));
  EXPECT_EQ(s.poll(settled), SupervisorStep::kDecide);
  s.decided(decision(ExplorerAction::kHover), settled);
  // That decision answered the leg's end: it is not ended again.
  EXPECT_FALSE(s.haveLeg());
  EXPECT_FALSE(s.legEnded(at(11.0)));
}

TEST(MissionSupervisor, LimitsNameTheKeyThatEndedTheMission) {
  SupervisorConfig c = headless();
  c.flight.max_flight_time = 100.0;
  c.max_path_length = 50.0;
  MissionSupervisor s(c);
  EXPECT_EQ(s.limitReached(99.9, 49.9), "");
  EXPECT_EQ(s.limitReached(100.0, 0.0).rfind("max_flight_time: ", 0), 0u);
  EXPECT_EQ(s.limitReached(1.0, 50.0).rfind("max_path_length: ", 0), 0u);
  MissionSupervisor unlimited(headless());
  EXPECT_EQ(unlimited.limitReached(1e9, 1e9), "");
}

TEST(MissionSupervisor, DoneEndsTheMissionAndTheTallyCountsEveryDecision) {
  SupervisorConfig c = headless(1.0);
  c.flight.start_spin = 0.0;
  MissionSupervisor s(c);
  s.takeOff(Eigen::Vector4d::Zero());
  const ExplorerAction actions[] = {ExplorerAction::kHover, ExplorerAction::kFly, ExplorerAction::kContinue,
                                    ExplorerAction::kFly};
  double t = 0.0;
  for (ExplorerAction a : actions) {
    ASSERT_EQ(s.poll(at(t)), SupervisorStep::kDecide);
    s.decided(decision(a, ReplanReason::kNone, 10.0 * (t + 1.0)), at(t));
    t += 1.0;
  }
  s.record(decision(ExplorerAction::kFly, ReplanReason::kPathBlocked, 5.0));  // checkPath between frontiers
  EXPECT_FALSE(s.done());
  ASSERT_EQ(s.poll(at(t)), SupervisorStep::kDecide);
  s.decided(decision(ExplorerAction::kDone, ReplanReason::kComplete, 1.0), at(t));
  EXPECT_TRUE(s.done());
  EXPECT_TRUE(s.completed());
  EXPECT_EQ(s.endReason(), std::string(toString(ReplanReason::kComplete)) + ": test");
  EXPECT_EQ(s.poll(at(t + 10.0)), SupervisorStep::kDone);
  const SupervisorTally& tally = s.tally();
  EXPECT_EQ(tally.fly, 3u);
  EXPECT_EQ(tally.hover, 1u);
  EXPECT_EQ(tally.cont, 1u);
  EXPECT_EQ(tally.done, 1u);
  EXPECT_EQ(tally.decisions(), 6u);
  EXPECT_DOUBLE_EQ(tally.max_decision_ms, 40.0);
  JsonWriter json;
  json.beginObject();
  tally.writeJson(&json);
  json.endObject();
  for (const char* key : {"\"decisions_fly\": 3", "\"decisions\": 6", "\"decision_wall_s_max\": 0.04",
                          "\"decision_wall_s_total\": 0.106"}) {
    EXPECT_NE(json.str().find(key), std::string::npos) << key << " in " << json.str();
  }
  s.reset();
  EXPECT_FALSE(s.done());
  EXPECT_EQ(s.tally().decisions(), 0u);
  EXPECT_EQ(s.poll(at(0.0)), SupervisorStep::kDecide);
}

TEST(MissionSupervisor, RecordsEveryCallForAReplay) {
  SupervisorConfig c = headless(1.0);
  MissionSupervisor s(c);
  std::vector<SupervisorCall> calls;
  s.setRecording(&calls);
  s.legSent(s.takeOff(Eigen::Vector4d::Zero()).back(), 12.0);
  SupervisorInput end = at(12.0);
  end.tracker_finished = true;
  s.poll(end);
  s.decided(decision(ExplorerAction::kHover), end);
  s.legDropped();
  ASSERT_EQ(calls.size(), 5u);
  EXPECT_EQ(calls[0].kind, SupervisorCall::Kind::kTakeOff);
  EXPECT_EQ(calls[1].kind, SupervisorCall::Kind::kLegSent);
  EXPECT_DOUBLE_EQ(calls[1].t_end, 12.0);
  EXPECT_EQ(calls[2].kind, SupervisorCall::Kind::kPoll);
  EXPECT_EQ(calls[2].step, SupervisorStep::kDecide);
  EXPECT_EQ(calls[3].kind, SupervisorCall::Kind::kDecided);
  EXPECT_EQ(calls[3].action, ExplorerAction::kHover);
  EXPECT_EQ(calls[4].kind, SupervisorCall::Kind::kLegDropped);
}
