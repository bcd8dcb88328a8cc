#include "surface_nbv/ros/latest_odometry.h"

#include "surface_nbv/ros/frontier_conversions.h"

namespace surface_nbv {

LatestOdometry::LatestOdometry(ros::NodeHandle& nh, const std::string& topic, const std::string& world_frame)
    : world_frame_(world_frame) {
  ros::SubscribeOptions options = ros::SubscribeOptions::create<nav_msgs::Odometry>(
      topic, 1, [this](const nav_msgs::OdometryConstPtr& msg) { onOdometry(msg); }, ros::VoidPtr(), &queue_);
  sub_ = nh.subscribe(options);
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  spinner_->start();
}

LatestOdometry::~LatestOdometry() {
  spinner_->stop();
  sub_.shutdown();
}

bool LatestOdometry::get(Eigen::Vector4d* pose, ros::Time* stamp) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!have_) return false;
  *pose = pose_;
  *stamp = stamp_;
  return true;
}

void LatestOdometry::onOdometry(const nav_msgs::OdometryConstPtr& msg) {
  const geometry_msgs::Pose& p = msg->pose.pose;
  if (msg->header.frame_id != world_frame_ || !allFinite(p.position) || !allFinite(p.orientation)) return;
  const Eigen::Vector4d pose(p.position.x, p.position.y, p.position.z, yawOf(p.orientation));
  std::lock_guard<std::mutex> lock(mutex_);
  if (have_ && msg->header.stamp < stamp_) return;
  pose_ = pose;
  stamp_ = msg->header.stamp;
  have_ = true;
}

}  // namespace surface_nbv
