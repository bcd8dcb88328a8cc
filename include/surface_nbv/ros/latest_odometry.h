// The newest odometry pose, received on a thread of its own.
//
// A node whose callbacks wait while it computes (nbv_planner deciding a leg)
// sees its odometry only afterwards, in the order it queued. LatestOdometry
// subscribes the same topic on a callback queue of its own, served by one
// AsyncSpinner thread, and keeps the newest valid pose (finite, in
// `world_frame`) behind a mutex: what the UAV's pose is at the moment the
// node sends its result. Messages that fail those checks are skipped here,
// and the node's own subscriber counts them.
#pragma once

#include <memory>
#include <mutex>
#include <string>

#include <Eigen/Core>
#include <nav_msgs/Odometry.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

namespace surface_nbv {

class LatestOdometry {
 public:
  LatestOdometry(ros::NodeHandle& nh, const std::string& topic, const std::string& world_frame);
  ~LatestOdometry();
  LatestOdometry(const LatestOdometry&) = delete;
  LatestOdometry& operator=(const LatestOdometry&) = delete;

  // The newest pose [x, y, z, yaw] and its stamp; false before the first.
  bool get(Eigen::Vector4d* pose, ros::Time* stamp) const;

 private:
  void onOdometry(const nav_msgs::OdometryConstPtr& msg);

  std::string world_frame_;
  mutable std::mutex mutex_;
  Eigen::Vector4d pose_ = Eigen::Vector4d::Zero();
  ros::Time stamp_;
  bool have_ = false;
  ros::CallbackQueue queue_;
  ros::Subscriber sub_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
};

}  // namespace surface_nbv
