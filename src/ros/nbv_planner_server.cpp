#include "surface_nbv/ros/nbv_planner_server.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <nav_msgs/Path.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "surface_nbv/PlannerStatus.h"
#include "surface_nbv/planning/leg_start.h"
#include "surface_nbv/planning/mission_report.h"
#include "surface_nbv/planning/supervisor_calls.h"
#include "surface_nbv/ros/frontier_conversions.h"
#include "surface_nbv/ros/planner_messages.h"

namespace surface_nbv {
namespace {

// Wall seconds between two copies of the roadmap into planner/markers.
constexpr double kRoadmapMarkerPeriod = 5.0;

// The UAV this close to the pose a leg was planned from flies it as planned.
constexpr double kLegStartTolerance = 0.3;  // m

}  // namespace

NbvPlannerServer::NbvPlannerServer(ros::NodeHandle nh, ros::NodeHandle priv, const PlannerNodeConfig& config)
    : nh_(nh),
      config_(config),
      stats_(nh_, "planner/stats", "nbv_planner", config.stats_period),
      feed_(nh_, config.map, config.collision, config.feed, "nbv_planner", &stats_),
      latest_(nh_, "odometry", config.world_frame),
      explorer_(config.explorer, config.path),
      supervisor_(config.supervisorConfig()),
      monitor_(config.max_tracking_error, config.off_track_time),
      markers_(nh_, "planner/markers", kRoadmapMarkerPeriod) {
  supervisor_.setRecording(&supervisor_calls_);
  if (Status s = explorer_.setMap(&feed_.collision(), config_.map.bounds); !s) {
    ROS_ERROR("nbv_planner: the path planner refused the map: %s", s.message().c_str());
  }
  state_ = config_.start_running ? State::kRunning : State::kStopped;
  frontier_sub_ = nh_.subscribe("surface/frontier", 2, &NbvPlannerServer::onFrontier, this);
  odometry_sub_ = nh_.subscribe("odometry", 20, &NbvPlannerServer::onOdometry, this);
  trajectory_pub_ = nh_.advertise<trajectory_msgs::MultiDOFJointTrajectory>("planner/trajectory", 1, true);
  path_pub_ = nh_.advertise<nav_msgs::Path>("planner/path", 1, true);
  status_pub_ = nh_.advertise<surface_nbv::PlannerStatus>("planner/status", 1, true);
  start_srv_ = priv.advertiseService("start", &NbvPlannerServer::onStart, this);
  stop_srv_ = priv.advertiseService("stop", &NbvPlannerServer::onStop, this);
  replan_srv_ = priv.advertiseService("replan", &NbvPlannerServer::onReplan, this);
  timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / config_.replan_rate), &NbvPlannerServer::onTimer, this);
  ROS_INFO("nbv_planner: %s, tick %.1f Hz, speed %.2f m/s, collision radius %.1f m, lambda_tc %.3f, lambda_ic %.3f, "
           "max_flight_time %.1f s (0: none)", stateName(), config_.replan_rate, config_.speed,
           config_.path.collision_radius, config_.explorer.graph.lambda_tc, config_.explorer.graph.lambda_ic,
           config_.max_flight_time);
  message_ = "waiting";
  publishStatus();
}

const char* NbvPlannerServer::stateName() const {
  switch (state_) {
    case State::kStopped: return "STOPPED";
    case State::kRunning: return "RUNNING";
    case State::kHovering: return "HOVERING";
    case State::kDone: return "DONE";
  }
  return "UNKNOWN";
}

void NbvPlannerServer::onFrontier(const surface_nbv::SurfaceFrontierConstPtr& msg) {
  if (have_frontier_ && msg->header.stamp < frontier_time_) {
    stats_.count("frontier_stale");
    return;
  }
  if (msg->header.frame_id != config_.world_frame) {
    stats_.count("frontier_wrong_frame");
    ROS_WARN_THROTTLE(5.0, "nbv_planner: surface/frontier in frame '%s', expected '%s'",
                      msg->header.frame_id.c_str(), config_.world_frame.c_str());
    return;
  }
  Frontier frontier;
  if (Status s = fromFrontierMsg(*msg, &frontier); !s) {
    stats_.count("frontier_malformed");
    ROS_WARN_THROTTLE(5.0, "nbv_planner: surface/frontier dropped: %s", s.message().c_str());
    return;
  }
  frontier_ = std::move(frontier);
  frontier_time_ = msg->header.stamp;
  have_frontier_ = frontier_new_ = true;
  stats_.count("frontiers");
  if (config_.prompt_ticks && state_ == State::kRunning && !supervisor_.spinning()) tick();
}

void NbvPlannerServer::onOdometry(const nav_msgs::OdometryConstPtr& msg) {
  if (have_odometry_ && msg->header.stamp < odometry_time_) {
    stats_.count("odometry_stale");
    return;
  }
  const geometry_msgs::Pose& pose = msg->pose.pose;
  if (!allFinite(pose.position) || !allFinite(pose.orientation)) {
    stats_.count("odometry_malformed");
    return;
  }
  if (msg->header.frame_id != config_.world_frame) {
    stats_.count("odometry_wrong_frame");
    ROS_WARN_THROTTLE(5.0, "nbv_planner: odometry in frame '%s', expected '%s'", msg->header.frame_id.c_str(),
                      config_.world_frame.c_str());
    return;
  }
  const Eigen::Vector4d uav(pose.position.x, pose.position.y, pose.position.z, yawOf(pose.orientation));
  if (have_odometry_) path_length_ += (uav.head<3>() - uav_.head<3>()).norm();
  uav_ = uav;
  odometry_time_ = msg->header.stamp;
  have_odometry_ = true;
  if (flying() && !have_mission_start_) {
    mission_start_ = odometry_time_;
    have_mission_start_ = true;
  }
  if (const std::string limit = flying() ? supervisor_.limitReached(flightTime(), path_length_) : ""; !limit.empty()) {
    const size_t colon = limit.find(": ");
    reason_ = limit.substr(0, colon);
    message_ = limit.substr(colon + 2);
    finish();
    return;
  }
  if (config_.prompt_ticks && state_ == State::kRunning && !supervisor_.spinning() && feed_.mirror().synced() &&
      supervisor_.legEnded(input(odometry_time_))) {
    tick();
  }
}

bool NbvPlannerServer::flying() const { return state_ == State::kRunning || state_ == State::kHovering; }

std_msgs::Header NbvPlannerServer::header() const {
  std_msgs::Header header;
  header.stamp = ros::Time::now();
  header.frame_id = config_.world_frame;
  return header;
}

double NbvPlannerServer::flightTime() const {
  return have_mission_start_ ? (odometry_time_ - mission_start_).toSec() : 0.0;
}

SupervisorInput NbvPlannerServer::input(const ros::Time& now) const {
  SupervisorInput in;
  in.t = have_mission_start_ ? (now - mission_start_).toSec() : 0.0;
  in.uav = uav_;
  in.path_length = path_length_;
  in.frontier_new = frontier_new_;
  in.has_target = explorer_.hasTarget();
  return in;
}

void NbvPlannerServer::sendLeg(const std::vector<Eigen::Vector4d>& points) {
  const double duration = publishTrajectory(points);
  supervisor_.legSent(points.back(), input(sent_at_).t + duration);
}

void NbvPlannerServer::tick() {
  if (state_ == State::kStopped || state_ == State::kDone) return;
  const ros::Time now = ros::Time::now();
  if (!have_odometry_ || !feed_.mirror().synced()) {
    message_ = !have_odometry_ ? "waiting for odometry" : "waiting for the map";
    publishStatus();
    return;
  }
  // Messages that waited in the callback queue while this node planned are
  // not stale: after its own work the node gives its callbacks a timeout's
  // grace to catch up. Without it every decision longer than the timeout
  // (a quarter of a wall second at 4x) held the UAV for stale odometry.
  // The map feed's snapshot requests and snapshots hold the callbacks back too.
  const double since_busy = (now - std::max(busy_until_, feed_.workedUntil())).toSec();
  if ((now - odometry_time_).toSec() > config_.odometry_timeout && since_busy > config_.odometry_timeout) {
    holdFor("odometry_stale", "no odometry for " + std::to_string((now - odometry_time_).toSec()) + " s");
    return;
  }
  if (!feed_.stamp().isZero() && (now - feed_.stamp()).toSec() > config_.map_timeout &&
      since_busy > config_.map_timeout) {
    holdFor("map_stale", "no map update for " + std::to_string((now - feed_.stamp()).toSec()) + " s");
    return;
  }
  if (!have_mission_start_) mission_start_ = odometry_time_, have_mission_start_ = true;
  if (!took_off_) {  // take-off: look around once before the first plan
    took_off_ = true;
    std::vector<Eigen::Vector4d> spin = supervisor_.takeOff(uav_);
    if (!spin.empty()) {
      spin.insert(spin.begin(), uav_);
      sendLeg(spin);
      reason_ = "take_off_spin";
      message_ = "turning in place before the first plan";
      publishStatus();
      return;
    }
  }
  double tracking_error = 0.0;
  if (supervisor_.haveLeg() && !supervisor_.spinning() &&
      monitor_.offTrack((now - sent_at_).toSec(), currentPose().head<3>(), &tracking_error)) {
    stats_.count("legs_off_track");
    ROS_WARN_THROTTLE(5.0, "nbv_planner: the UAV stayed %.1f m from its trajectory for %.1f s (a tracker that refused "
                      "it?): planning the leg again from where it is", tracking_error, config_.off_track_time);
    supervisor_.legDropped();
    explorer_.legCancelled();
    frontier_new_ = true;  // decide now
  }
  SupervisorInput in = input(now);
  in.frontier_new = frontier_new_ || (state_ == State::kHovering && (reason_ == "odometry_stale" || reason_ == "map_stale"));
  const bool leg_ended = supervisor_.legEnded(in);
  const SupervisorStep step = supervisor_.poll(in);
  if (supervisor_.spinning()) return;
  if (step != SupervisorStep::kDecide || !have_frontier_) {
    // Between frontiers: is the current leg still free?
    if (supervisor_.haveLeg() && feed_.refresh() != MapFeed::Refresh::kUnchanged) {
      explorer_.mapChanged();
      const ExplorerDecision d = explorer_.checkPath(uav_);
      if (d.action != ExplorerAction::kContinue) supervisor_.record(d), act(d);
      busy_until_ = ros::Time::now();
    }
    return;
  }
  frontier_new_ = false;
  if (feed_.refresh() != MapFeed::Refresh::kUnchanged) explorer_.mapChanged();
  const ExplorerDecision d = supervisor_.decide(&explorer_, frontier_, in);
  stats_.recordMs(d.timings.total_ms);
  act(d);
  busy_until_ = ros::Time::now();  // after the markers too (the roadmap's edges take time)
  // The flight seconds the UAV hovered at a leg's end until its next leg came.
  if (leg_ended) leg_end_wait_s_ += std::max(0.0, (ros::Time::now() - now).toSec());
}

void NbvPlannerServer::act(const ExplorerDecision& d) {
  last_timings_ = d.timings;
  if (d.reason != ReplanReason::kNone) reason_ = toString(d.reason);
  message_ = d.message;
  stats_.count(std::string("decision_") + toString(d.action));
  switch (d.action) {
    case ExplorerAction::kContinue:
      if (state_ == State::kHovering) state_ = State::kRunning;
      break;
    case ExplorerAction::kFly: {
      std::vector<Eigen::Vector4d> points{uav_};
      points.insert(points.end(), d.path.begin(), d.path.end());
      startAtTheUav(&points);
      sendLeg(resamplePath(points, config_.trajectory_spacing));
      state_ = State::kRunning;
      break;
    }
    case ExplorerAction::kHover:
      hold(d.message);
      return;
    case ExplorerAction::kDone:
      finish();
      return;
  }
  publishStatus();
  markers_.publish(header(), explorer_, uav_);
}

Eigen::Vector4d NbvPlannerServer::currentPose() const {
  Eigen::Vector4d pose;
  ros::Time stamp;
  return latest_.get(&pose, &stamp) && stamp > odometry_time_ ? pose : uav_;
}

void NbvPlannerServer::startAtTheUav(std::vector<Eigen::Vector4d>* points) {
  if (config_.leg_restart_reach <= 0.0) return;
  // Without a newer pose, currentPose() is uav_, the leg's first point: kUnchanged.
  const LegStart start = restartLeg(currentPose(), feed_.collision(), explorer_.pathPlanner().clearance(),
                                    config_.leg_restart_reach, kLegStartTolerance, points);
  if (start != LegStart::kUnchanged) stats_.count(std::string("leg_start_") + toString(start));
}

bool NbvPlannerServer::cancelLeg() {
  if (have_odometry_) publishTrajectory({currentPose()});
  supervisor_.legDropped();
  explorer_.legCancelled();
  return have_odometry_;
}

void NbvPlannerServer::hold(const std::string& why) {
  cancelLeg();
  if (flying()) state_ = State::kHovering;
  message_ = why;
  stats_.count("holds");
  ROS_WARN_THROTTLE(5.0, "nbv_planner: holding the current pose: %s", why.c_str());
  publishStatus();
}

void NbvPlannerServer::holdFor(const std::string& reason, const std::string& why) {
  if (state_ == State::kHovering && reason_ == reason) return;
  reason_ = reason;
  hold(why);
}

void NbvPlannerServer::finish() {
  cancelLeg();
  state_ = State::kDone;
  ROS_INFO("nbv_planner: mission over after %.1f s of flight and %.1f m: %s %s", flightTime(), path_length_,
           reason_.c_str(), message_.c_str());
  writeReport();
  saveMissionFiles(config_.save_map_service, config_.export_mesh_service);
  publishStatus();
  markers_.publish(header(), explorer_, uav_);
  stats_.publishNow();
  if (config_.exit_when_done) {
    ROS_INFO("nbv_planner: exit_when_done: shutting down");
    ros::WallDuration(0.5).sleep();  // let the latched status and hold trajectory go out
    ros::shutdown();
  }
}

void NbvPlannerServer::writeReport() const {
  if (config_.report_directory.empty()) return;
  MissionReport report;
  report.progress = progress();
  report.max_flight_time = config_.max_flight_time;
  report.holds = stats_.get("holds");
  report.uav = uav_;
  report.tally = supervisor_.tally();
  report.ises = frontier_.ises.size();
  report.ises_inside = frontier_.insideCount();
  report.explorer = explorer_.stats();
  report.leg_end_wait_s = leg_end_wait_s_;
  report.leg_time_budget = config_.explorer.leg_time_budget;
  report.blacklisted = explorer_.blacklist().size();
  // What explore_sim.launch derived from the scene for the keys its config left out (nbv_scene).
  if (std::string derived; ros::param::get("/scene_defaults", derived)) report.scene_defaults = derived;
  if (Status s = writeMissionReport(config_.report_directory, report); !s) {
    ROS_WARN("nbv_planner: %s", s.message().c_str());
  }
  if (Status s = writeSupervisorCalls(config_.report_directory + "/supervisor_calls.csv", supervisor_calls_); !s) {
    ROS_WARN("nbv_planner: %s", s.message().c_str());
  }
}

double NbvPlannerServer::publishTrajectory(const std::vector<Eigen::Vector4d>& points) {
  const std_msgs::Header header = this->header();
  nav_msgs::Path path;
  const trajectory_msgs::MultiDOFJointTrajectory trajectory =
      trajectoryMsg(header, points, config_.speed, config_.yaw_rate, &path);
  trajectory_pub_.publish(trajectory);
  path_pub_.publish(path);
  monitor_.setReference(trajectoryReference(trajectory));
  sent_at_ = header.stamp;
  return trajectory.points.empty() ? 0.0 : trajectory.points.back().time_from_start.toSec();
}

MissionProgress NbvPlannerServer::progress() const {
  return {stateName(), reason_, message_, flightTime(), path_length_};
}

void NbvPlannerServer::publishStatus() {
  status_pub_.publish(plannerStatusMsg(header(), progress(), frontier_, explorer_, last_timings_));
}

bool NbvPlannerServer::onStart(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  res.success = true;
  if (flying()) {
    res.message = std::string("already ") + stateName();
    return true;
  }
  if (state_ == State::kDone) {
    explorer_.reset();
    supervisor_.reset();
    supervisor_calls_.clear();
    have_mission_start_ = false;  // a new mission, a new flight clock
    res.message = "running a new mission on the current map";
  } else {
    res.message = "running";
  }
  state_ = State::kRunning;
  frontier_new_ = have_frontier_;
  reason_ = "started";
  message_ = res.message;
  publishStatus();
  return true;
}

bool NbvPlannerServer::onStop(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  const bool was_done = state_ == State::kDone;
  state_ = was_done ? State::kDone : State::kStopped;
  res.success = true;
  if (cancelLeg()) {
    res.message = was_done ? "mission already over; holding the current pose" : "stopped; holding the current pose";
  } else {
    res.message = "stopped; no odometry yet, no hold trajectory sent";
  }
  explorer_.replan();
  message_ = res.message;
  publishStatus();
  return true;
}

bool NbvPlannerServer::onReplan(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  explorer_.replan();
  frontier_new_ = have_frontier_;
  res.success = true;
  res.message = flying() ? "recomputing the tour at the next tick"
                         : std::string("tour recomputed once ") + stateName() + " ends (~start)";
  return true;
}

}  // namespace surface_nbv
