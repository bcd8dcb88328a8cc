// Parameters of nbv_planner. From the shared namespace: voxel_size, w_th,
// bounds_min, bounds_max (the mirrored map) and lambda_tc, lambda_ic (eq. 5),
// one copy for every node; the explorer's settings from the mission section
// (mission_namespace); the rest are the node's own (~). Unknown private
// keys are refused.
#pragma once

#include <string>

#include "surface_nbv/config/config_keys.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/tsdf_config.h"
#include "surface_nbv/planning/cluster_graph.h"
#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/planning/path_planner.h"
#include "surface_nbv/ros/map_feed.h"
#include "surface_nbv/ros/param_reader.h"

namespace surface_nbv {

// speed, yaw_rate, leg_lookahead, leg_yaw_tolerance, max_flight_time (0: no
// limit) and start_spin are MissionFlightConfig's (config_keys.h): the mission
// section's keys (nbv_mission's), then the node's own (~) over them.
struct PlannerNodeConfig : MissionFlightConfig {
  std::string shared_namespace = kSharedNamespace;
  // The explorer's keys (travel_yaw, reach_tolerance, ...) and the path
  // budget (path_iterations, path_time_budget) of the YAML's mission section,
  // which nbv_mission reads too; private parameters override them.
  std::string mission_namespace = "/mission";
  TsdfConfig map;                 // voxel size, w_th and bounds of the mirrored map
  // graph.lambda_tc, graph.lambda_ic from the shared namespace; the rest ~.
  // The node's leg_time_budget defaults to 5 wall seconds (nbv_mission's to
  // none): the flight goes on while the node plans, and failing leg attempts
  // at the full path budget held it for minutes at 4x (README, session 15).
  ExplorerConfig explorer = [] {
    ExplorerConfig e;
    e.leg_time_budget = 5.0;
    return e;
  }();
  // collision_radius, time_budget, seed of the PRM. The node's lattice
  // fallback is on (0.3 m; nbv_mission's is off): under leg_time_budget a
  // roadmap that cannot find the tight passage a target lies behind spent
  // every decision's budget, one hover after another for up to 190 s of
  // flight, where the lattice finds it (session 19, docs/mission_history.md).
  PathPlannerConfig path = [] {
    PathPlannerConfig p;
    p.lattice_step = 0.3;
    return p;
  }();
  CollisionConfig collision;
  std::string world_frame = "world";
  double replan_rate = 2.0;       // Hz: ticks; a tick decides on a new frontier, an ended leg or ~replan
  // Also tick at once when a frontier arrives and when odometry shows the
  // leg ended (ROS time): the wall-clock timer alone left the UAV idle for up
  // to 1 / replan_rate wall seconds (2 s of flight at 4x) after every leg.
  bool prompt_ticks = true;
  double trajectory_spacing = 0.5;  // m between trajectory points along the path
  bool start_running = false;     // true: RUNNING from the start, else waits for ~start
  double leg_settle = 0.5;        // s after a leg's last point before the leg counts as ended
  // A leg decided while the UAV flew on starts where the UAV is when it is
  // sent (newest odometry, latest_odometry.h), joined straight to the
  // farthest point of its first leg_restart_reach metres that keeps the
  // planner's clearance (planning/leg_start.h). Decisions of a wall second
  // at 4x left the UAV over 2 m from the leg's first point and the tracker
  // refused the leg. 0: off (the leg starts where the decision began).
  double leg_restart_reach = 3.0;  // m
  // A leg the UAV does not follow (farther than max_tracking_error from the
  // trajectory's reference point for off_track_time, ROS time: a tracker
  // that refused it, or lost it) is given up without a failure on its target
  // and planned again at once from where the UAV is; before, the node waited
  // out the leg's whole duration and then counted its target unreachable.
  // 0: off.
  double max_tracking_error = 3.0;  // m
  double off_track_time = 2.0;      // s
  double odometry_timeout = 1.0;  // s (ROS time) without odometry: hover
  double map_timeout = 10.0;      // s (ROS time) without a map update while running: hover
  std::string report_directory;   // where DONE writes mission_report.json; empty = nowhere
  bool exit_when_done = false;    // shut the node down once DONE (with required="true" the launch ends)
  std::string save_map_service;   // called with "mission.tsdf" when DONE; empty = not called
  std::string export_mesh_service;  // called with "mission.ply" when DONE; empty = not called
  MapFeedConfig feed;             // snapshot_service, update_queue, snapshot_retry (map_feed.h)
  double stats_period = 1.0;

  // Names the first bad key, e.g. "speed expected in (0, 20] m/s".
  Status validate() const;
  // The mission's rules as nbv_planner applies them: a decision on every new
  // frontier, a leg ended leg_settle after its reference (no word from the tracker).
  SupervisorConfig supervisorConfig() const;
};

Status loadPlannerParams(const ros::NodeHandle& priv, PlannerNodeConfig* config);

}  // namespace surface_nbv
