// mission_report.json, what nbv_planner (ros/nbv_planner_server.h) writes
// into its report_directory when the mission ends: built here, ROS-free,
// from a plain MissionReport the node fills. scripts/explore_ros and
// test_mission_node read its keys; they are those of the report as first
// written, in the same order.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/planning/mission_supervisor.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// Where a planner's mission stands: what planner/status and the report both say.
struct MissionProgress {
  std::string state;          // STOPPED, RUNNING, HOVERING or DONE
  std::string reason;         // the last decision's reason, or why hovering or done
  std::string message;        // human-readable detail
  double flight_time = 0.0;   // s since the mission's first odometry
  double path_length = 0.0;   // m flown, from odometry
};

struct MissionReport {
  MissionProgress progress;
  double max_flight_time = 0.0;  // s; 0: no limit
  size_t holds = 0;              // times the planner held the UAV's pose
  Eigen::Vector4d uav = Eigen::Vector4d::Zero();  // the last pose [x, y, z, yaw]
  SupervisorTally tally;         // the decisions and legs (decisions_fly ... legs_dropped)
  size_t ises = 0, ises_inside = 0;  // |C| and |C_ins| of the last frontier
  ExplorerStats explorer;        // full_recomputes, local_updates, legs, leg_failures, budget_stops, lattice_legs
  double leg_end_wait_s = 0.0;   // flight s hovered at leg ends while the next leg was decided
  double leg_time_budget = 0.0;  // s, ExplorerConfig::leg_time_budget
  size_t blacklisted = 0;        // places the explorer gave up on
  // What explore_sim.launch derived from the scene for the keys its config
  // left out (nbv_scene's /scene_defaults); unset: the key is left out.
  std::optional<std::string> scene_defaults;
};

// The report as JSON (JsonWriter's layout): state, reason, message,
// flight_time_s, max_flight_time_s, path_length_m, holds, uav {x, y, z, yaw},
// the tally's keys, ises, ises_inside, full_recomputes, local_updates, legs,
// leg_failures, budget_stops, lattice_legs, leg_end_wait_s,
// leg_time_budget_s, blacklisted and scene_defaults.
std::string missionReportJson(const MissionReport& report);

// Writes missionReportJson() to `directory`/mission_report.json, creating
// the directory if needed.
Status writeMissionReport(const std::string& directory, const MissionReport& report);

}  // namespace surface_nbv
