#include "surface_nbv/ros/mpc_tracker_server.h"

#include "surface_nbv/config/config_keys.h"

#include <chrono>
#include <cmath>

#include <nav_msgs/Odometry.h>
#include <rosgraph_msgs/Clock.h>

namespace surface_nbv {

Status TrackerNodeConfig::validate() const {
  if (Status s = sim.validate(); !s) return s;
  if (!initial.allFinite()) return Status::Error("initial_position / initial_yaw expected finite");
  if (world_frame.empty() || body_frame.empty() || world_frame == body_frame) {
    return Status::Error("world_frame and body_frame expected two different frame names");
  }
  if (!std::isfinite(real_time_factor) || real_time_factor <= 0.0 || real_time_factor > 1000.0) {
    return Status::Error("real_time_factor expected in (0, 1000]");
  }
  if (!std::isfinite(publish_rate) || publish_rate <= 0.0 || publish_rate > 1000.0) {
    return Status::Error("publish_rate expected in (0, 1000] Hz");
  }
  if (!std::isfinite(stats_period) || stats_period <= 0.0) return Status::Error("stats_period expected > 0");
  return Status::Ok();
}

Status loadTrackerParams(const ros::NodeHandle& priv, TrackerNodeConfig* c) {
  ParamReader r(priv);
  r.get("sim_dt", &c->sim.sim_dt);
  r.get("control_period", &c->sim.control_period);
  r.get("max_start_distance", &c->sim.max_start_distance);
  std::string tracker_namespace = kTrackerNamespace;
  r.get("tracker_namespace", &tracker_namespace);
  ParamReader shared((ros::NodeHandle(tracker_namespace)));
  readTrackerKeys(shared, &c->sim);  // the config's tracker section (nbv_mission's), then ~
  readTrackerKeys(r, &c->sim);
  shared.checkUnknown();
  if (Status s = shared.status(); !s) return s;
  r.get("horizon", &c->sim.mpc.horizon);
  r.get("mpc_dt", &c->sim.mpc.dt);
  r.get("q_position", &c->sim.mpc.q_position);
  r.get("q_velocity", &c->sim.mpc.q_velocity);
  r.get("q_yaw", &c->sim.mpc.q_yaw);
  r.get("r_acceleration", &c->sim.mpc.r_acceleration);
  // The mission's take-off pose, mission/start = [x, y, z, yaw] (the key
  // nbv_mission reads), unless ~initial_position / ~initial_yaw are given.
  std::vector<double> start;
  if (ros::param::get("/mission/start", start)) {
    if (start.size() != 4) return Status::Error("/mission/start expected [x, y, z, yaw]");
    c->initial.p_W = Eigen::Vector3d(start[0], start[1], start[2]);
    c->initial.yaw = start[3];
  }
  r.get("initial_position", &c->initial.p_W);
  r.get("initial_yaw", &c->initial.yaw);
  r.get("world_frame", &c->world_frame);
  r.get("body_frame", &c->body_frame);
  r.get("real_time_factor", &c->real_time_factor);
  r.get("publish_rate", &c->publish_rate);
  r.get("stats_period", &c->stats_period);
  r.checkUnknown();
  if (Status s = r.status(); !s) return s;
  if (Status s = c->validate(); !s) return Status::Error(priv.getNamespace() + "/" + s.message());
  return Status::Ok();
}

Status fromTrajectoryMsg(const trajectory_msgs::MultiDOFJointTrajectory& msg, double now, Trajectory* trajectory) {
  if (msg.points.empty()) return Status::Error("trajectory has no points");
  const double start = msg.header.stamp.isZero() ? now : msg.header.stamp.toSec();
  std::vector<TrajectoryPoint> points;
  points.reserve(msg.points.size());
  for (size_t i = 0; i < msg.points.size(); ++i) {
    const trajectory_msgs::MultiDOFJointTrajectoryPoint& in = msg.points[i];
    if (in.transforms.size() != 1) {
      return Status::Error("point " + std::to_string(i) + " has " + std::to_string(in.transforms.size()) +
                           " transforms, expected 1");
    }
    const geometry_msgs::Transform& tf = in.transforms[0];
    const geometry_msgs::Quaternion& q = tf.rotation;
    const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!(std::abs(norm - 1.0) <= 1e-3)) {
      return Status::Error("point " + std::to_string(i) + " has a rotation of norm " + std::to_string(norm) +
                           ", expected a unit quaternion");
    }
    TrajectoryPoint p;
    p.t = start + in.time_from_start.toSec();
    p.p_W = Eigen::Vector3d(tf.translation.x, tf.translation.y, tf.translation.z);
    p.yaw = std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
    if (!in.velocities.empty()) {
      p.has_velocity = true;
      p.v_W = Eigen::Vector3d(in.velocities[0].linear.x, in.velocities[0].linear.y, in.velocities[0].linear.z);
    }
    points.push_back(p);
  }
  *trajectory = Trajectory(std::move(points));
  return Status::Ok();
}

MpcTrackerServer::MpcTrackerServer(ros::NodeHandle nh, const TrackerNodeConfig& config)
    : nh_(nh), config_(config), sim_(config.sim, config.initial), stats_(nh_, "tracker/stats", "mpc_tracker", 1.0) {
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  odom_pub_ = nh_.advertise<nav_msgs::Odometry>("odometry", 10);
  trajectory_sub_ = nh_.subscribe("planner/trajectory", 2, &MpcTrackerServer::onTrajectory, this);
  timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / config_.publish_rate), &MpcTrackerServer::onTimer, this);
  ROS_INFO("mpc_tracker: simulated UAV at [%.1f %.1f %.1f] yaw %.2f, %.1fx real time, MPC horizon %d x %.2f s",
           config_.initial.p_W.x(), config_.initial.p_W.y(), config_.initial.p_W.z(), config_.initial.yaw,
           config_.real_time_factor, config_.sim.mpc.horizon, config_.sim.mpc.dt);
  publishState();
}

void MpcTrackerServer::onTrajectory(const trajectory_msgs::MultiDOFJointTrajectoryConstPtr& msg) {
  Trajectory trajectory;
  Status s = fromTrajectoryMsg(*msg, sim_.time(), &trajectory);
  if (s) s = sim_.setTrajectory(trajectory);
  if (!s) {
    stats_.count("trajectories_refused");
    ROS_WARN_THROTTLE(2.0, "mpc_tracker: trajectory refused, holding the pose: %s", s.message().c_str());
    return;
  }
  stats_.count("trajectories_accepted");
}

void MpcTrackerServer::onTimer(const ros::WallTimerEvent&) {
  const auto t0 = std::chrono::steady_clock::now();
  sim_.runUntil(sim_.time() + config_.real_time_factor / config_.publish_rate);
  stats_.recordMs(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  publishState();
}

void MpcTrackerServer::publishState() {
  const ros::Time now(sim_.time());
  rosgraph_msgs::Clock clock;
  clock.clock = now;
  clock_pub_.publish(clock);
  const UavState& s = sim_.state();
  const Eigen::Quaterniond q(Eigen::AngleAxisd(s.yaw, Eigen::Vector3d::UnitZ()));
  nav_msgs::Odometry odom;
  odom.header.stamp = now;
  odom.header.frame_id = config_.world_frame;
  odom.child_frame_id = config_.body_frame;
  odom.pose.pose.position.x = s.p_W.x();
  odom.pose.pose.position.y = s.p_W.y();
  odom.pose.pose.position.z = s.p_W.z();
  odom.pose.pose.orientation.w = q.w();
  odom.pose.pose.orientation.x = q.x();
  odom.pose.pose.orientation.y = q.y();
  odom.pose.pose.orientation.z = q.z();
  const Eigen::Vector3d v_B = q.conjugate() * s.v_W;  // REP 147: twist in the child frame
  odom.twist.twist.linear.x = v_B.x();
  odom.twist.twist.linear.y = v_B.y();
  odom.twist.twist.linear.z = v_B.z();
  odom.twist.twist.angular.z = s.yaw_rate;
  odom_pub_.publish(odom);
  geometry_msgs::TransformStamped tf;
  tf.header = odom.header;
  tf.child_frame_id = config_.body_frame;
  tf.transform.translation.x = s.p_W.x();
  tf.transform.translation.y = s.p_W.y();
  tf.transform.translation.z = s.p_W.z();
  tf.transform.rotation = odom.pose.pose.orientation;
  broadcaster_.sendTransform(tf);
  stats_.set("mode", static_cast<uint64_t>(sim_.mode()));
}

}  // namespace surface_nbv
