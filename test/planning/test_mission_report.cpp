// mission_report.json (planning/mission_report.h): nbv_planner's report at a
// mission's end, its keys, their order and values as scripts/explore_ros and
// test_mission_node read them, and the file it is written to.
#include "surface_nbv/planning/mission_report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace surface_nbv;

namespace {

MissionReport sampleReport() {
  MissionReport r;
  r.progress.state = "DONE";
  r.progress.reason = "complete";
  r.progress.message = "no ISE of C_ins remains";
  r.progress.flight_time = 812.25;
  r.progress.path_length = 301.5;
  r.max_flight_time = 1920.0;
  r.holds = 3;
  r.uav = Eigen::Vector4d(1.5, -2.0, 3.25, 0.5);
  r.tally.fly = 40;
  r.tally.hover = 2;
  r.tally.cont = 7;
  r.tally.done = 1;
  r.tally.decision_ms = {10.0, 30.0, 20.0};
  r.tally.max_decision_ms = 30.0;
  r.tally.legs_sent = 41;
  r.tally.legs_dropped = 4;
  r.ises = 120;
  r.ises_inside = 0;
  r.explorer.full_recomputes = 12;
  r.explorer.local_updates = 35;
  r.explorer.legs = 41;
  r.explorer.leg_failures = 5;
  r.explorer.budget_stops = 2;
  r.explorer.lattice_legs = 6;
  r.leg_end_wait_s = 14.5;
  r.leg_time_budget = 5.0;
  r.blacklisted = 9;
  return r;
}

// The number after "key": at the top level or in an object, NaN if absent
// (as test_mission_node reads the report).
double number(const std::string& text, const std::string& key) {
  const size_t at = text.find("\"" + key + "\": ");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(text.c_str() + at + key.size() + 4, nullptr);
}

}  // namespace

TEST(MissionReport, KeysInOrderWithTheirValues) {
  const std::string json = missionReportJson(sampleReport());
  // Every key of the report as nbv_planner first wrote it, in that order.
  const std::vector<std::string> keys = {
      "\"state\": \"DONE\"", "\"reason\": \"complete\"", "\"message\": \"no ISE of C_ins remains\"",
      "\"flight_time_s\": 812.25", "\"max_flight_time_s\": 1920", "\"path_length_m\": 301.5", "\"holds\": 3",
      "\"uav\": {", "\"x\": 1.5", "\"y\": -2", "\"z\": 3.25", "\"yaw\": 0.5", "}",
      "\"decisions_fly\": 40", "\"decisions_hover\": 2", "\"decisions_continue\": 7", "\"decisions_done\": 1",
      "\"decisions\": 3", "\"decision_wall_s_total\": 0.06", "\"decision_wall_s_median\": 0.02",
      "\"decision_wall_s_p90\": 0.03", "\"decision_wall_s_max\": 0.03", "\"legs_sent\": 41", "\"legs_dropped\": 4",
      "\"ises\": 120", "\"ises_inside\": 0", "\"full_recomputes\": 12", "\"local_updates\": 35", "\"legs\": 41",
      "\"leg_failures\": 5", "\"budget_stops\": 2", "\"lattice_legs\": 6", "\"leg_end_wait_s\": 14.5",
      "\"leg_time_budget_s\": 5", "\"blacklisted\": 9"};
  size_t from = 0;
  for (const std::string& key : keys) {
    const size_t at = json.find(key, from);
    ASSERT_NE(at, std::string::npos) << key << " after offset " << from << " in " << json;
    from = at + key.size();
  }
  EXPECT_EQ(json.find("scene_defaults"), std::string::npos) << "left out when nbv_scene derived nothing";
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.substr(json.size() - 2), "}\n");
  EXPECT_DOUBLE_EQ(number(json, "flight_time_s"), 812.25);
  EXPECT_DOUBLE_EQ(number(json, "path_length_m"), 301.5);
}

TEST(MissionReport, SceneDefaultsAndEscapedMessage) {
  MissionReport r = sampleReport();
  r.progress.reason = "max_flight_time";
  r.progress.message = "flew \"1920\" s";
  r.scene_defaults = "bounds_min: [-8, -8, 0]\nvoxel_size: 0.1";
  const std::string json = missionReportJson(r);
  EXPECT_NE(json.find("\"reason\": \"max_flight_time\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"message\": \"flew \\\"1920\\\" s\""), std::string::npos) << json;
  const size_t blacklisted = json.find("\"blacklisted\": 9");
  const size_t defaults = json.find("\"scene_defaults\": \"bounds_min: [-8, -8, 0]\\nvoxel_size: 0.1\"");
  ASSERT_NE(defaults, std::string::npos) << json;
  EXPECT_GT(defaults, blacklisted) << "the last key";
}

TEST(MissionReport, AnEmptyTallyReportsZeroDecisionTimes) {
  MissionReport r;
  r.progress.state = "RUNNING";
  const std::string json = missionReportJson(r);
  EXPECT_EQ(number(json, "decisions"), 0.0);
  EXPECT_EQ(number(json, "decision_wall_s_median"), 0.0);
  EXPECT_EQ(number(json, "decision_wall_s_max"), 0.0);
  EXPECT_EQ(number(json, "max_flight_time_s"), 0.0);
}

TEST(MissionReport, WritesTheFileIntoANewDirectory) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("surface_nbv_mission_report_" + std::to_string(::getpid())) / "out";
  std::filesystem::remove_all(dir.parent_path());
  const MissionReport r = sampleReport();
  ASSERT_TRUE(writeMissionReport(dir.string(), r).ok());
  std::stringstream text;
  text << std::ifstream(dir / "mission_report.json").rdbuf();
  EXPECT_EQ(text.str(), missionReportJson(r));
  // A directory that cannot be created: the error names the file.
  const std::filesystem::path blocker = dir / "a_file";
  std::ofstream(blocker) << "x";
  const Status s = writeMissionReport((blocker / "sub").string(), r);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("mission_report.json"), std::string::npos) << s.message();
  std::filesystem::remove_all(dir.parent_path());
}
