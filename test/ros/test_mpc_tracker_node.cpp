// The simulated UAV follows a published trajectory; odometry, TF and /clock
// agree; a malformed trajectory is refused and the UAV holds its pose.
#include <gtest/gtest.h>

#include <cmath>
#include <mutex>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>

#include "surface_nbv/NodeStats.h"

namespace {

trajectory_msgs::MultiDOFJointTrajectory straightLine(double length, double speed) {
  trajectory_msgs::MultiDOFJointTrajectory traj;  // zero stamp: starts now
  const int n = 11;
  for (int i = 0; i < n; ++i) {
    trajectory_msgs::MultiDOFJointTrajectoryPoint p;
    geometry_msgs::Transform tf;
    tf.translation.x = 1.0 + length * i / (n - 1);
    tf.translation.y = 2.0;
    tf.translation.z = 3.0;
    tf.rotation.w = 1.0;
    p.transforms.push_back(tf);
    p.time_from_start = ros::Duration(length * i / (n - 1) / speed);
    traj.points.push_back(p);
  }
  return traj;
}

}  // namespace

TEST(MpcTrackerNode, FollowsATrajectoryWithConsistentClockOdometryAndTf) {
  ros::NodeHandle nh;
  std::mutex mutex;
  nav_msgs::Odometry odom;
  int odoms = 0;
  bool stamps_monotone = true;
  ros::Time last_stamp, last_clock;
  surface_nbv::NodeStats stats;
  ros::Subscriber clock_sub = nh.subscribe<rosgraph_msgs::Clock>("/clock", 100, [&](const rosgraph_msgs::ClockConstPtr& c) {
    std::lock_guard<std::mutex> l(mutex);
    last_clock = c->clock;
  });
  ros::Subscriber odom_sub = nh.subscribe<nav_msgs::Odometry>("odometry", 100, [&](const nav_msgs::OdometryConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex);
    stamps_monotone = stamps_monotone && m->header.stamp > last_stamp;
    last_stamp = m->header.stamp;
    odom = *m;
    ++odoms;
  });
  ros::Subscriber stats_sub = nh.subscribe<surface_nbv::NodeStats>(
      "tracker/stats", 5, [&](const surface_nbv::NodeStatsConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        stats = *m;
      });
  ros::Publisher traj_pub = nh.advertise<trajectory_msgs::MultiDOFJointTrajectory>("planner/trajectory", 1, true);
  tf2_ros::Buffer tf_buffer;
  tf2_ros::TransformListener listener(tf_buffer);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  for (int i = 0; i < 100 && odoms == 0; ++i) ros::WallDuration(0.1).sleep();
  ASSERT_GT(odoms, 0) << "no odometry";

  // A malformed trajectory first: refused, the UAV holds at its start.
  trajectory_msgs::MultiDOFJointTrajectory bad = straightLine(4.0, 0.5);
  bad.points[3].transforms[0].translation.x = NAN;
  traj_pub.publish(bad);
  ros::WallDuration(1.0).sleep();
  {
    std::lock_guard<std::mutex> l(mutex);
    EXPECT_NEAR(odom.pose.pose.position.x, 1.0, 0.05);
    EXPECT_NEAR(odom.pose.pose.position.y, 2.0, 0.05);
  }

  // 4 m at 0.5 m/s: 8 simulated seconds, under 2 s of wall time at 5x.
  traj_pub.publish(straightLine(4.0, 0.5));
  ros::WallDuration(3.5).sleep();
  std::lock_guard<std::mutex> l(mutex);
  EXPECT_NEAR(odom.pose.pose.position.x, 5.0, 0.05);
  EXPECT_NEAR(odom.pose.pose.position.y, 2.0, 0.05);
  EXPECT_NEAR(odom.pose.pose.position.z, 3.0, 0.05);
  EXPECT_TRUE(stamps_monotone);
  EXPECT_LE(odom.header.stamp, last_clock) << "odometry ahead of /clock";
  EXPECT_GT(last_clock.toSec(), 9.0) << "the simulated clock does not run at 5x";
  EXPECT_EQ(odom.header.frame_id, "world");
  EXPECT_EQ(odom.child_frame_id, "base_link");
  geometry_msgs::TransformStamped tf;
  ASSERT_NO_THROW(tf = tf_buffer.lookupTransform("world", "base_link", odom.header.stamp));
  EXPECT_NEAR(tf.transform.translation.x, odom.pose.pose.position.x, 1e-9);
  EXPECT_NEAR(tf.transform.translation.y, odom.pose.pose.position.y, 1e-9);
  uint64_t refused = 0, accepted = 0;
  for (const auto& c : stats.counters) {
    if (c.name == "trajectories_refused") refused = c.count;
    if (c.name == "trajectories_accepted") accepted = c.count;
  }
  EXPECT_EQ(refused, 1u);
  EXPECT_EQ(accepted, 1u);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_mpc_tracker_node");
  return RUN_ALL_TESTS();
}
