// The nbv_planner node: the paper's Fig. 1 loop (planning/explorer.h) on
// ROS topics. It keeps a MapMirror of tsdf/update (asking the mapper for a
// snapshot on a gap) with a CollisionMap, the last surface/frontier and the
// last odometry, and on each tick (replan_rate, wall clock; with prompt_ticks
// also on each frontier and on the odometry that shows the leg ended) while
// RUNNING carries out what its MissionSupervisor (planning/mission_supervisor.h,
// the rules nbv_mission's loop follows too) says:
//   - turns start_spin in place once at the first start (to see around),
//   - hands a new frontier, or the end of the current leg (its last point's
//     time plus leg_settle, ROS time, or leg_lookahead's rule), to
//     Explorer::update and acts on the decision: a new leg -> planner/trajectory (MultiDOFJointTrajectory at
//     `speed`, yaw timed by `yaw_rate`) and planner/path; hover -> a hold
//     trajectory at the current pose (HOVERING); done -> hold, DONE, the
//     mission report (and the supervisor's calls, to replay), the map and
//     mesh saved through the mapper's services,
//   - between frontiers, re-checks the current leg against the updated map
//     (Explorer::checkPath) and re-plans it when blocked,
//   - hovers when odometry is older than odometry_timeout or the map has not
//     been updated for map_timeout (both ROS time), and resumes when they come
//     back; for a timeout after one of its own decisions it waits (what queued
//     while it planned is not stale).
// With max_flight_time > 0 the mission ends as on done (hold, DONE, report,
// map and mesh) with reason max_flight_time once the odometry stamp is that
// many seconds past the mission's first odometry (checked on each odometry
// message). A respawned planner starts its own clock.
// planner/status (surface_nbv/PlannerStatus, latched) says the state, the
// last reason, ISE counts, tour, flown length and stage timings, and
// planner/markers shows the tour, the current leg, the next target, the
// blacklisted places, the tour's cluster-graph arcs and the roadmap (copied
// at most every 5 wall seconds); it is built only while someone subscribes.
//
// Services (std_srvs/Trigger, valid in any state, always answer): ~start
// (RUNNING; after DONE it starts a new mission on the current map), ~stop
// (STOPPED, holding the current pose), ~replan (the next tick recomputes the
// whole tour). Inputs that are stale (older stamp than the last accepted one),
// in the wrong frame or malformed are dropped and counted on planner/stats.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <std_msgs/Header.h>

#include "surface_nbv/SurfaceFrontier.h"
#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/planning/mission_report.h"
#include "surface_nbv/planning/mission_supervisor.h"
#include "surface_nbv/ros/latest_odometry.h"
#include "surface_nbv/ros/map_feed.h"
#include "surface_nbv/ros/planner_messages.h"
#include "surface_nbv/ros/planner_params.h"
#include "surface_nbv/ros/stats_reporter.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/tracking/reference_monitor.h"

namespace surface_nbv {

class NbvPlannerServer {
 public:
  enum class State { kStopped, kRunning, kHovering, kDone };

  NbvPlannerServer(ros::NodeHandle nh, ros::NodeHandle priv, const PlannerNodeConfig& config);

 private:
  void onFrontier(const surface_nbv::SurfaceFrontierConstPtr& msg);
  void onOdometry(const nav_msgs::OdometryConstPtr& msg);
  void onTimer(const ros::WallTimerEvent&) { tick(); }
  // One decision step (the timer's, and prompt_ticks' on frontier and leg end).
  void tick();
  bool onStart(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool onStop(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool onReplan(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);

  void act(const ExplorerDecision& d);
  // Holds the current pose; HOVERING (or keeps STOPPED / DONE) with `why`.
  void hold(const std::string& why);
  // Holds for `reason` (a stale input), unless already HOVERING for it.
  void holdFor(const std::string& reason, const std::string& why);
  // Sends a hold at the UAV's pose (false without odometry: nothing sent) and
  // forgets the leg it was flying, here and in the explorer, so the next
  // decision plans a new one instead of continuing a leg nobody flies.
  bool cancelLeg();
  // Holds, DONE, the report, the map and mesh; reason_ and message_ say why.
  void finish();
  // RUNNING or HOVERING: a mission is being flown.
  bool flying() const;
  // s of odometry time since the first odometry of the mission, 0 before it.
  double flightTime() const;
  // The state, reason, message, flight time and path flown (status and report).
  MissionProgress progress() const;
  // Stamped now, in world_frame.
  std_msgs::Header header() const;
  // What the supervisor is told at ROS time `now`.
  SupervisorInput input(const ros::Time& now) const;
  // Publishes a leg (or the take-off spin) from its first point and tells the supervisor.
  void sendLeg(const std::vector<Eigen::Vector4d>& points);
  // Publishes the points as a trajectory from now; returns its duration [s].
  double publishTrajectory(const std::vector<Eigen::Vector4d>& points);
  // The newest odometry pose: latest_'s when it is newer than uav_.
  Eigen::Vector4d currentPose() const;
  // A leg decided from uav_ starts where the UAV is now (restartLeg, leg_restart_reach).
  void startAtTheUav(std::vector<Eigen::Vector4d>* points);
  void publishStatus();
  // mission_report.json and supervisor_calls.csv into report_directory
  // (when set): planning/mission_report.h, planning/supervisor_calls.h.
  void writeReport() const;
  const char* stateName() const;

  ros::NodeHandle nh_;
  PlannerNodeConfig config_;
  StatsReporter stats_;
  MapFeed feed_;
  LatestOdometry latest_;
  Explorer explorer_;
  MissionSupervisor supervisor_;  // take-off, leg ends, decisions, limits, tally (mission_supervisor.h)
  // Its calls this mission (one poll per tick, ~150 bytes each), for
  // supervisor_calls.csv beside the report (planning/supervisor_calls.h).
  std::vector<SupervisorCall> supervisor_calls_;
  ReferenceMonitor monitor_;      // is the UAV following the last trajectory sent (max_tracking_error)?
  PlannerMarkerPublisher markers_;  // planner/markers, while someone subscribes
  ros::Subscriber frontier_sub_, odometry_sub_;
  ros::Publisher trajectory_pub_, path_pub_, status_pub_;
  ros::ServiceServer start_srv_, stop_srv_, replan_srv_;
  ros::WallTimer timer_;

  State state_ = State::kStopped;
  Frontier frontier_;
  bool have_frontier_ = false, frontier_new_ = false;
  ros::Time frontier_time_;
  Eigen::Vector4d uav_ = Eigen::Vector4d::Zero();  // x, y, z, yaw
  bool have_odometry_ = false;
  ros::Time odometry_time_, mission_start_;
  double leg_end_wait_s_ = 0.0;           // flight s hovered at leg ends while the next leg was decided
  ros::Time busy_until_;             // ROS time the last decision and its messages were done (stale checks wait a timeout past it)
  bool have_mission_start_ = false;  // mission_start_ is the mission's first odometry stamp
  double path_length_ = 0.0;
  bool took_off_ = false;          // the take-off was asked for (once per node: not again after ~start)
  ros::Time sent_at_;  // the stamp of the last trajectory sent
  std::string reason_ = "none", message_;
  ExplorerTimings last_timings_;
};

}  // namespace surface_nbv
