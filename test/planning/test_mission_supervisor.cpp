// The mission's rules (planning/mission_supervisor.h): take-off spin, leg
// ends (tracker, settle, lookahead), decisions by period or new frontier,
// limits, the tally and its report keys; the calls as a file
// (planning/supervisor_calls.h).
#include "surface_nbv/planning/mission_supervisor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "surface_nbv/planning/supervisor_calls.h"

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

namespace {

std::string tempFile(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("test_mission_supervisor_" + name)).string();
}

}  // namespace

TEST(SupervisorCalls, AFileReadsBackToTheCallsItWasWrittenFrom) {
  MissionSupervisor s(headless(1.0));
  std::vector<SupervisorCall> calls;
  s.setRecording(&calls);
  s.legSent(s.takeOff(Eigen::Vector4d(1.0 / 3.0, -2e-7, 4.5, M_PI)).back(), 12.345678901234567);
  SupervisorInput end = at(12.0, Eigen::Vector4d(0.1, 0.2, 0.3, -0.7));
  end.tracker_finished = true;
  end.has_target = true;
  end.path_length = 7.25;
  s.poll(end);
  ExplorerDecision d = decision(ExplorerAction::kDone, ReplanReason::kComplete, 17.5);
  d.message = "no ISE of C_ins remains, 3 outside\nsecond line";
  s.decided(d, end);
  s.record(decision(ExplorerAction::kHover, ReplanReason::kPathBlocked));
  s.legDropped();
  ASSERT_EQ(calls.size(), 6u);
  EXPECT_EQ(calls[0].spin, 5u);  // 6.2832 rad is a hair over four quarter turns

  const std::string file = tempFile("calls.csv");
  ASSERT_TRUE(writeSupervisorCalls(file, calls).ok());
  std::vector<SupervisorCall> read;
  const Status r = readSupervisorCalls(file, &read);
  std::filesystem::remove(file);
  ASSERT_TRUE(r.ok()) << r.message();
  ASSERT_EQ(read.size(), calls.size());
  for (size_t i = 0; i < calls.size(); ++i) {
    const SupervisorCall &a = calls[i], &b = read[i];
    EXPECT_EQ(a.kind, b.kind) << i;
    EXPECT_EQ(a.in.t, b.in.t) << i;
    EXPECT_EQ(a.in.uav, b.in.uav) << i;  // exactly: 17 digits
    EXPECT_EQ(a.in.path_length, b.in.path_length) << i;
    EXPECT_EQ(a.in.tracker_finished, b.in.tracker_finished) << i;
    EXPECT_EQ(a.in.has_target, b.in.has_target) << i;
    EXPECT_EQ(a.goal, b.goal) << i;
    EXPECT_EQ(a.t_end, b.t_end) << i;
    EXPECT_EQ(a.step, b.step) << i;
    EXPECT_EQ(a.spin, b.spin) << i;
    EXPECT_EQ(a.action, b.action) << i;
    EXPECT_EQ(a.reason, b.reason) << i;
    EXPECT_EQ(a.decision_ms, b.decision_ms) << i;
  }
  EXPECT_EQ(read[3].message, "no ISE of C_ins remains, 3 outside second line");  // commas kept, the break a space

  MissionSupervisor replay(headless(1.0));
  ASSERT_TRUE(replaySupervisorCalls(read, &replay).ok());
  EXPECT_TRUE(replay.done());
  EXPECT_TRUE(replay.completed());
  EXPECT_EQ(replay.endReason(), "complete: no ISE of C_ins remains, 3 outside second line");
  EXPECT_EQ(replay.tally().hover, 1u);
  EXPECT_EQ(replay.tally().legs_dropped, 0u);  // the leg's end was answered by the decision
  // A poll recorded with another answer is named.
  read[2].step = SupervisorStep::kWait;
  MissionSupervisor other(headless(1.0));
  const Status differs = replaySupervisorCalls(read, &other);
  ASSERT_FALSE(differs.ok());
  EXPECT_EQ(differs.message(), "call 2 (poll at t = 12): decide, recorded wait");
}

TEST(SupervisorCalls, AMalformedFileNamesItsFirstBadLine) {
  const std::string good =
      "poll,1,0,0,2,0,0,0,1,0,0,0,0,0,0,decide,0,continue,none,0,fine, with a comma";
  const auto readRows = [](const std::vector<std::string>& rows, std::vector<SupervisorCall>* calls) {
    const std::string file = tempFile("bad.csv");
    std::ofstream(file) << [&] {
      std::string text;
      for (const std::string& r : rows) text += r + "\n";
      return text;
    }();
    const Status s = readSupervisorCalls(file, calls);
    std::filesystem::remove(file);
    return s;
  };
  const std::string header =
      "kind,t,x,y,z,yaw,path_length,tracker_finished,frontier_new,has_target,goal_x,goal_y,goal_z,goal_yaw,t_end,step,"
      "spin,action,reason,decision_ms,message";
  std::vector<SupervisorCall> calls(3);
  ASSERT_TRUE(readRows({header, good}, &calls).ok());
  ASSERT_EQ(calls.size(), 1u);
  EXPECT_TRUE(calls[0].in.frontier_new);
  EXPECT_EQ(calls[0].message, "fine, with a comma");
  const struct {
    std::vector<std::string> rows;
    const char* error;
  } cases[] = {
      {{"kind,t"}, "line 1: expected the header"},
      {{header, good, "poll,1,2"}, "line 3: expected 21 columns"},
      {{header, "jump,1,0,0,2,0,0,0,1,0,0,0,0,0,0,decide,0,continue,none,0,"}, "line 2: unknown kind 'jump'"},
      {{header, "poll,nan?,0,0,2,0,0,0,1,0,0,0,0,0,0,decide,0,continue,none,0,"}, "line 2: column 2 is not a number"},
      {{header, "poll,1,0,0,2,0,0,2,1,0,0,0,0,0,0,decide,0,continue,none,0,"}, "line 2: column 8 expected 0 or 1"},
      {{header, "poll,1,0,0,2,0,0,0,1,0,0,0,0,0,0,maybe,0,continue,none,0,"}, "line 2: unknown step 'maybe'"},
      {{header, "take_off,1,0,0,2,0,0,0,1,0,0,0,0,0,0,wait,-1,continue,none,0,"}, "line 2: spin expected a count"},
      {{header, "poll,1,0,0,2,0,0,0,1,0,0,0,0,0,0,decide,0,unknown,none,0,"}, "line 2: unknown action 'unknown'"},
      {{header, "poll,1,0,0,2,0,0,0,1,0,0,0,0,0,0,decide,0,fly,sideways,0,"}, "line 2: unknown reason 'sideways'"},
  };
  for (const auto& c : cases) {
    const Status s = readRows(c.rows, &calls);
    ASSERT_FALSE(s.ok()) << c.error;
    EXPECT_NE(s.message().find(c.error), std::string::npos) << s.message();
    EXPECT_EQ(calls.size(), 1u) << "a bad file leaves the calls as they were";
  }
  EXPECT_FALSE(readSupervisorCalls(tempFile("missing.csv"), &calls).ok());
}
