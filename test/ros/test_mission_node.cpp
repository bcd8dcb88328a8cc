// The whole ROS mission on the box (mission.test, mission_faults.test,
// mission_time_limit.test): waits for planner/status DONE, checks the end
// reason (~expected_reason, default complete; "a|b" accepts either, for the
// faulted run, where lost frames and restarts can leave the last places
// unreachable on the wall clock), the flight time against
// ~max_flight_time when set (within ~flight_time_tolerance s), the saved map,
// mesh and report, replays the planner's supervisor_calls.csv through a
// MissionSupervisor built from the planner's own parameters (the same
// answers, tally and end as its report: it took the rules' decisions and no
// others), then evaluates the mesh the planner had the mapper export.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include <ros/ros.h>

#include "surface_nbv/PlannerStatus.h"
#include "surface_nbv/eval/evaluator.h"
#include "surface_nbv/planning/supervisor_calls.h"
#include "surface_nbv/ros/planner_params.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/sim/scene_source.h"

using namespace surface_nbv;

namespace {

// The number after "key": in the planner's mission_report.json, NaN if absent.
double jsonNumber(const std::string& text, const std::string& key) {
  const size_t at = text.find("\"" + key + "\": ");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(text.c_str() + at + key.size() + 4, nullptr);
}

}  // namespace

TEST(Mission, BoxMissionEndsWithTheExpectedReasonAndFiles) {
  ros::NodeHandle nh, priv("~");
  std::string out_dir, expected_reason = "complete";
  double min_coverage = 0.95, max_flight_time = 0.0, tolerance = 2.0;
  ASSERT_TRUE(priv.getParam("out_dir", out_dir));
  priv.getParam("min_coverage", min_coverage);
  priv.getParam("expected_reason", expected_reason);
  priv.getParam("max_flight_time", max_flight_time);
  priv.getParam("flight_time_tolerance", tolerance);
  for (const char* f : {"/mission.ply", "/mission.tsdf", "/mission_report.json", "/supervisor_calls.csv"}) std::filesystem::remove(out_dir + f);
  std::mutex mutex;
  PlannerStatus status;
  size_t running = 0;
  ros::Subscriber sub = nh.subscribe<PlannerStatus>("planner/status", 10, [&](const PlannerStatusConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex);
    status = *m;
    running += m->state == "RUNNING" ? 1 : 0;
  });
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(400.0);
  bool done = false;
  while (!done && ros::WallTime::now() < deadline) {
    ros::WallDuration(0.5).sleep();
    std::lock_guard<std::mutex> l(mutex);
    done = status.state == "DONE";
  }
  std::lock_guard<std::mutex> l(mutex);
  ASSERT_TRUE(done) << "no DONE within the time limit; last state " << status.state << " (" << status.reason << ": "
                    << status.message << ")";
  EXPECT_GT(running, 0u);
  bool accepted = false;
  for (size_t at = 0; at <= expected_reason.size();) {
    const size_t bar = std::min(expected_reason.find('|', at), expected_reason.size());
    accepted = accepted || status.reason == expected_reason.substr(at, bar - at);
    at = bar + 1;
  }
  EXPECT_TRUE(accepted) << "ended " << status.reason << ", expected " << expected_reason << ": " << status.message;
  // The report and the replay must agree with the reason the mission gave.
  expected_reason = status.reason;
  EXPECT_GT(status.path_length, 5.0);
  std::printf("mission: %.1f s of flight, %.1f m, %u legs, %u full / %u local updates, %u blacklisted: %s\n",
              status.flight_time, status.path_length, status.legs, status.full_recomputes, status.local_updates,
              status.blacklisted, status.message.c_str());
  if (max_flight_time > 0.0) {
    EXPECT_GE(status.flight_time, max_flight_time);
    EXPECT_LE(status.flight_time, max_flight_time + tolerance);
  }
  // The planner asked the mapper to save the map and export the mesh.
  for (int i = 0; i < 20 && !std::filesystem::exists(out_dir + "/mission.ply"); ++i) ros::WallDuration(0.5).sleep();
  ASSERT_TRUE(std::filesystem::exists(out_dir + "/mission_report.json"));
  EXPECT_TRUE(std::filesystem::exists(out_dir + "/mission.tsdf"));
  std::stringstream report;
  report << std::ifstream(out_dir + "/mission_report.json").rdbuf();
  EXPECT_NE(report.str().find("\"reason\": \"" + expected_reason + "\""), std::string::npos) << report.str();
  EXPECT_NEAR(jsonNumber(report.str(), "flight_time_s"), status.flight_time, 1e-3) << report.str();

  // The planner's calls to its supervisor, replayed with the rules read from
  // its parameters by the node's own loader.
  PlannerNodeConfig planner;
  ASSERT_TRUE(loadPlannerParams(ros::NodeHandle("/nbv_planner"), &planner).ok());
  std::vector<SupervisorCall> calls;
  const Status read = readSupervisorCalls(out_dir + "/supervisor_calls.csv", &calls);
  ASSERT_TRUE(read.ok()) << read.message();
  MissionSupervisor replay(planner.supervisorConfig());
  const Status replayed = replaySupervisorCalls(calls, &replay);
  EXPECT_TRUE(replayed.ok()) << replayed.message();
  size_t polls = 0;
  for (const SupervisorCall& c : calls) polls += c.kind == SupervisorCall::Kind::kPoll;
  std::printf("replayed %zu supervisor calls (%zu polls, %zu decisions)\n", calls.size(), polls,
              replay.tally().decisions());
  EXPECT_GT(polls, 10u);
  EXPECT_EQ(static_cast<double>(replay.tally().fly), jsonNumber(report.str(), "decisions_fly"));
  EXPECT_EQ(static_cast<double>(replay.tally().hover), jsonNumber(report.str(), "decisions_hover"));
  EXPECT_EQ(static_cast<double>(replay.tally().decisions()), jsonNumber(report.str(), "decisions"));
  EXPECT_EQ(static_cast<double>(replay.tally().legs_sent), jsonNumber(report.str(), "legs_sent"));
  if (replay.done()) {
    EXPECT_EQ(replay.endReason().substr(0, expected_reason.size() + 1), expected_reason + ":") << replay.endReason();
  } else {
    EXPECT_FALSE(replay.limitReached(status.flight_time, status.path_length).empty())
        << "the planner ended the mission (" << status.reason << ") where its rules had not";
  }

  TriangleMesh box, reconstruction;
  SceneConfig scene;
  scene.scene = "box";
  ASSERT_TRUE(loadScene(scene, &box).ok());
  ASSERT_TRUE(loadMesh(out_dir + "/mission.ply", MeshLoadOptions(), &reconstruction).ok());
  EvalConfig eval;
  eval.voxel_size = 0.1;
  eval.min_range = 0.5;
  eval.max_range = 8.0;
  eval.threads = 2;
  EvalResult result;
  ASSERT_TRUE(Evaluator(eval).evaluate(box, reconstruction, &result).ok());
  std::printf("coverage %.2f %%, RMSE %.2f cm\n", 100.0 * result.coverage.coverage(), 100.0 * result.error_stats.rmse);
  EXPECT_GE(result.coverage.coverage(), min_coverage);
  EXPECT_LT(result.error_stats.rmse, 0.1);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_mission_node");
  return RUN_ALL_TESTS();
}
