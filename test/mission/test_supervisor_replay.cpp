// The headless mission takes the decisions its MissionSupervisor gives, and
// only those: a mission's calls, replayed through a fresh supervisor with
// the same rules, get the same answers, the same tally and the same end.
// (nbv_planner drives the same class; its rostests fly it: mission_*.test.)
#include "surface_nbv/mission/mission_runner.h"

#include <gtest/gtest.h>

#include "surface_nbv/sim/procedural_scenes.h"

using namespace surface_nbv;

namespace {

ExplorerDecision recorded(const SupervisorCall& c) {
  ExplorerDecision d;
  d.action = c.action;
  d.reason = c.reason;
  d.message = c.message;
  d.timings.total_ms = c.decision_ms;
  return d;
}

}  // namespace

TEST(SupervisorReplay, AHeadlessMissionReplaysToTheSameDecisions) {
  MissionConfig config;
  ASSERT_TRUE(loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/box.yaml", &config).ok());
  config.max_flight_time = 90.0;
  config.path.iteration_budget = 20000;
  config.path.time_budget = 60.0;
  config.leg_lookahead = 1.0;  // the lookahead rule too
  TriangleMesh mesh;
  ASSERT_TRUE(loadScene(config.scene, &mesh).ok());
  std::unique_ptr<RaycastScene> scene;
  ASSERT_TRUE(RaycastScene::create(mesh, &scene).ok());
  MissionRunner runner(config, *scene);
  std::vector<SupervisorCall> calls;
  runner.setSupervisorRecording(&calls);
  const MissionResult result = runner.run();
  ASSERT_TRUE(result.status.ok()) << result.status.message();

  size_t polls = 0, decided = 0, legs = 0;
  for (const SupervisorCall& c : calls) {
    polls += c.kind == SupervisorCall::Kind::kPoll;
    decided += c.kind == SupervisorCall::Kind::kDecided;
    legs += c.kind == SupervisorCall::Kind::kLegSent;
  }
  // One poll per frame, one decision per frontier update, the spin and legs flown.
  EXPECT_EQ(polls, result.frames);
  EXPECT_EQ(decided, result.events.size());
  EXPECT_GE(decided, 10u);
  EXPECT_GE(legs, 3u);
  EXPECT_EQ(result.tally.decisions(), decided);
  EXPECT_EQ(result.tally.legs_sent, legs);
  ASSERT_EQ(calls.front().kind, SupervisorCall::Kind::kTakeOff);

  MissionSupervisor replay(config.supervisorConfig());
  size_t i = 0;
  for (const SupervisorCall& c : calls) {
    switch (c.kind) {
      case SupervisorCall::Kind::kTakeOff: EXPECT_FALSE(replay.takeOff(c.in.uav).empty()); break;
      case SupervisorCall::Kind::kLegSent: replay.legSent(c.goal, c.t_end); break;
      case SupervisorCall::Kind::kLegDropped: replay.legDropped(); break;
      case SupervisorCall::Kind::kPoll: ASSERT_EQ(replay.poll(c.in), c.step) << "call " << i << " at t = " << c.in.t; break;
      case SupervisorCall::Kind::kDecided: replay.decided(recorded(c), c.in); break;
      case SupervisorCall::Kind::kRecord: replay.record(recorded(c)); break;
    }
    ++i;
  }
  EXPECT_EQ(replay.tally().fly, result.tally.fly);
  EXPECT_EQ(replay.tally().hover, result.tally.hover);
  EXPECT_EQ(replay.tally().legs_dropped, result.tally.legs_dropped);
  EXPECT_EQ(replay.done(), result.end_reason == replay.endReason() && !replay.endReason().empty());
  if (!replay.done()) {
    EXPECT_EQ(replay.limitReached(result.flight_time, result.path_length), result.end_reason);
  }

  // A supervisor with other rules (a decision every 3 s, not 1 s) answers
  // the same calls differently: the replay is not a tautology.
  SupervisorConfig other = config.supervisorConfig();
  other.frontier_period = 3.0 * config.frontier_period;
  MissionSupervisor slow(other);
  size_t differ = 0;
  for (const SupervisorCall& c : calls) {
    if (c.kind == SupervisorCall::Kind::kTakeOff) slow.takeOff(c.in.uav);
    if (c.kind == SupervisorCall::Kind::kLegSent) slow.legSent(c.goal, c.t_end);
    if (c.kind == SupervisorCall::Kind::kLegDropped) slow.legDropped();
    if (c.kind == SupervisorCall::Kind::kPoll) differ += slow.poll(c.in) != c.step;
    if (c.kind == SupervisorCall::Kind::kDecided) slow.decided(recorded(c), c.in);
  }
  EXPECT_GT(differ, 0u);
}
