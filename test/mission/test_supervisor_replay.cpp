// The headless mission takes the decisions its MissionSupervisor gives, and
// only those: a mission's calls, written to supervisor_calls.csv, read back
// and replayed through a fresh supervisor with the same rules, get the same
// answers, the same tally and the same end. (nbv_planner's calls get the
// same replay in test_mission_node, with the rules read from its parameters.)
#include "surface_nbv/mission/mission_runner.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "surface_nbv/planning/supervisor_calls.h"

#include "surface_nbv/sim/procedural_scenes.h"

using namespace surface_nbv;

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

  // Through the file, as nbv_planner's calls come to test_mission_node.
  const std::string file = (std::filesystem::temp_directory_path() / "test_supervisor_replay_calls.csv").string();
  ASSERT_TRUE(writeSupervisorCalls(file, calls).ok());
  std::vector<SupervisorCall> read;
  ASSERT_TRUE(readSupervisorCalls(file, &read).ok());
  std::filesystem::remove(file);
  ASSERT_EQ(read.size(), calls.size());

  MissionSupervisor replay(config.supervisorConfig());
  const Status replayed = replaySupervisorCalls(read, &replay);
  ASSERT_TRUE(replayed.ok()) << replayed.message();
  EXPECT_EQ(replay.tally().fly, result.tally.fly);
  EXPECT_EQ(replay.tally().hover, result.tally.hover);
  EXPECT_EQ(replay.tally().legs_dropped, result.tally.legs_dropped);
  EXPECT_EQ(replay.tally().decision_ms, result.tally.decision_ms);
  EXPECT_EQ(replay.done(), result.end_reason == replay.endReason() && !replay.endReason().empty());
  if (!replay.done()) {
    EXPECT_EQ(replay.limitReached(result.flight_time, result.path_length), result.end_reason);
  }

  // A supervisor with other rules (a decision every 3 s, not 1 s) answers
  // the same calls differently: the replay is not a tautology.
  SupervisorConfig other = config.supervisorConfig();
  other.frontier_period = 3.0 * config.frontier_period;
  MissionSupervisor slow(other);
  const Status differs = replaySupervisorCalls(read, &slow);
  EXPECT_FALSE(differs.ok());
  EXPECT_NE(differs.message().find("recorded decide"), std::string::npos) << differs.message();
  // Nor does one without the take-off spin.
  SupervisorConfig no_spin = config.supervisorConfig();
  no_spin.flight.start_spin = 0.0;
  MissionSupervisor still(no_spin);
  const Status spin = replaySupervisorCalls(read, &still);
  EXPECT_FALSE(spin.ok());
  EXPECT_NE(spin.message().find("call 0 (take_off"), std::string::npos) << spin.message();
}
