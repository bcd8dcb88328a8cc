// The mpc_tracker node: the simulated UAV. It follows planner/trajectory
// (trajectory_msgs/MultiDOFJointTrajectory) with the linear MPC of the
// tracking concern, integrates the 4-DOF model at a fixed step, owns /clock
// (real_time_factor simulated seconds per wall second), and publishes
// odometry (nav_msgs/Odometry, twist in base_link) and TF world -> base_link
// stamped with the simulated time. A refused trajectory (empty, NaN, times
// not increasing, too far away) is counted and the UAV holds its pose.
// On a real UAV this node is not launched: the stack's controller takes
// planner/trajectory and the stack publishes odometry and TF.
#pragma once

#include <memory>
#include <string>

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "surface_nbv/ros/param_reader.h"
#include "surface_nbv/ros/stats_reporter.h"
#include "surface_nbv/tracking/tracker_sim.h"

namespace surface_nbv {

struct TrackerNodeConfig {
  TrackerSimConfig sim;
  UavState initial;
  std::string world_frame = "world";
  std::string body_frame = "base_link";
  double real_time_factor = 1.0;   // simulated seconds per wall second
  double publish_rate = 100.0;     // Hz of wall time: clock, odometry and TF
  double stats_period = 1.0;

  Status validate() const;
};

// The UAV's limits (drag, v_max, a_max, yaw_rate_max, jerk_max) come from the
// config's `tracker` section (~tracker_namespace, "/tracker" by default: the
// section nbv_mission reads), then from the node's own parameters, which win.
Status loadTrackerParams(const ros::NodeHandle& priv, TrackerNodeConfig* config);

// Converts a trajectory message to absolute times on the simulated clock
// (header.stamp + time_from_start; a zero stamp means `now`). Points need one
// transform each, its rotation a unit quaternion (norm within 1e-3: an unset,
// all-zero one is refused); velocities are used when given.
Status fromTrajectoryMsg(const trajectory_msgs::MultiDOFJointTrajectory& msg, double now, Trajectory* trajectory);

class MpcTrackerServer {
 public:
  MpcTrackerServer(ros::NodeHandle nh, const TrackerNodeConfig& config);

 private:
  void onTrajectory(const trajectory_msgs::MultiDOFJointTrajectoryConstPtr& msg);
  void onTimer(const ros::WallTimerEvent&);
  void publishState();

  ros::NodeHandle nh_;
  TrackerNodeConfig config_;
  TrackerSim sim_;
  tf2_ros::TransformBroadcaster broadcaster_;
  StatsReporter stats_;
  ros::Subscriber trajectory_sub_;
  ros::Publisher clock_pub_, odom_pub_;
  ros::WallTimer timer_;
};

}  // namespace surface_nbv
