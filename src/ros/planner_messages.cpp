#include "surface_nbv/ros/planner_messages.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>

#include "surface_nbv/FilePath.h"
#include "surface_nbv/util/angles.h"

namespace surface_nbv {
namespace {

geometry_msgs::Quaternion yawQuaternion(double yaw) {
  geometry_msgs::Quaternion q;
  q.w = std::cos(0.5 * yaw);
  q.z = std::sin(0.5 * yaw);
  return q;
}

visualization_msgs::Marker lineStrip(const std_msgs::Header& header, const std::string& ns,
                                     const std::vector<Eigen::Vector4d>& points, float r, float g, float b,
                                     int type = visualization_msgs::Marker::LINE_STRIP) {
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = ns;
  m.id = 0;
  m.type = points.empty() ? visualization_msgs::Marker::LINE_STRIP : type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = 0.1;
  m.color.r = r;
  m.color.g = g;
  m.color.b = b;
  m.color.a = 1.0f;
  for (const Eigen::Vector4d& p : points) m.points.push_back(tf2::toMsg(Eigen::Vector3d(p.head<3>())));
  return m;
}

}  // namespace

trajectory_msgs::MultiDOFJointTrajectory trajectoryMsg(const std_msgs::Header& header,
                                                       const std::vector<Eigen::Vector4d>& points, double speed,
                                                       double yaw_rate, nav_msgs::Path* path) {
  trajectory_msgs::MultiDOFJointTrajectory trajectory;
  trajectory.header = header;
  trajectory.joint_names = {"base_link"};
  if (path) path->header = header, path->poses.clear();
  double t = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector4d& p = points[i];
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    if (i > 0) {
      const Eigen::Vector4d& a = points[i - 1];
      const double dt = std::max((p.head<3>() - a.head<3>()).norm() / speed, std::abs(wrapAngle(p.w() - a.w())) / yaw_rate);
      t += std::max(dt, 1e-3);
    }
    if (i + 1 < points.size()) {
      const Eigen::Vector3d step = points[i + 1].head<3>() - p.head<3>();
      if (step.norm() > 1e-9) v = speed * step.normalized();
    }
    trajectory_msgs::MultiDOFJointTrajectoryPoint point;
    geometry_msgs::Transform tf;
    tf.translation.x = p.x();
    tf.translation.y = p.y();
    tf.translation.z = p.z();
    tf.rotation = yawQuaternion(p.w());
    point.transforms.push_back(tf);
    geometry_msgs::Twist twist;
    twist.linear.x = v.x();
    twist.linear.y = v.y();
    twist.linear.z = v.z();
    point.velocities.push_back(twist);
    point.time_from_start = ros::Duration(t);
    trajectory.points.push_back(point);
    if (!path) continue;
    geometry_msgs::PoseStamped pose;
    pose.header = header;
    pose.pose.position = tf2::toMsg(Eigen::Vector3d(p.head<3>()));
    pose.pose.orientation = tf.rotation;
    path->poses.push_back(pose);
  }
  return trajectory;
}

std::vector<std::pair<double, Eigen::Vector3d>> trajectoryReference(
    const trajectory_msgs::MultiDOFJointTrajectory& trajectory) {
  std::vector<std::pair<double, Eigen::Vector3d>> reference;
  for (const trajectory_msgs::MultiDOFJointTrajectoryPoint& point : trajectory.points) {
    const geometry_msgs::Vector3& p = point.transforms.front().translation;
    reference.emplace_back(point.time_from_start.toSec(), Eigen::Vector3d(p.x, p.y, p.z));
  }
  return reference;
}

visualization_msgs::MarkerArray plannerMarkers(const std_msgs::Header& header, const Explorer& explorer,
                                               const Eigen::Vector4d& uav, bool with_roadmap) {
  visualization_msgs::MarkerArray markers;
  std::vector<Eigen::Vector4d> tour{uav};
  tour.insert(tour.end(), explorer.tour().begin(), explorer.tour().end());
  markers.markers.push_back(lineStrip(header, "tour", tour, 1.0f, 0.6f, 0.0f));
  markers.markers.push_back(lineStrip(header, "leg", explorer.currentPath(), 0.0f, 0.8f, 0.2f));
  std::vector<Eigen::Vector4d> target;
  if (explorer.hasTarget() && !explorer.tour().empty()) target.push_back(explorer.tour().front());
  visualization_msgs::Marker t = lineStrip(header, "target", target, 1.0f, 0.0f, 1.0f,
                                           visualization_msgs::Marker::SPHERE_LIST);
  t.scale.x = t.scale.y = t.scale.z = 0.6;
  markers.markers.push_back(t);
  std::vector<Eigen::Vector4d> black;
  for (const Eigen::Vector3d& b : explorer.blacklist()) black.emplace_back(b.x(), b.y(), b.z(), 0.0);
  visualization_msgs::Marker bl = lineStrip(header, "blacklisted", black, 0.1f, 0.1f, 0.1f,
                                            visualization_msgs::Marker::SPHERE_LIST);
  bl.scale.x = bl.scale.y = bl.scale.z = 0.4;
  markers.markers.push_back(bl);
  if (with_roadmap) {
    visualization_msgs::Marker roadmap = lineStrip(header, "roadmap", {}, 0.6f, 0.6f, 0.6f);
    roadmap.type = visualization_msgs::Marker::LINE_LIST;
    roadmap.scale.x = 0.02;
    roadmap.color.a = 0.4f;
    for (const auto& [a, b] : explorer.pathPlanner().roadmapEdges(20000)) {
      roadmap.points.push_back(tf2::toMsg(a));
      roadmap.points.push_back(tf2::toMsg(b));
    }
    markers.markers.push_back(std::move(roadmap));
  }
  visualization_msgs::Marker graph = lineStrip(header, "cluster_graph", {}, 1.0f, 1.0f, 1.0f);
  graph.type = visualization_msgs::Marker::LINE_LIST;
  graph.scale.x = 0.08;
  double best = 0.0;
  for (const TourArc& arc : explorer.tourArcs()) best = std::max(best, arc.utility);
  for (const TourArc& arc : explorer.tourArcs()) {
    std_msgs::ColorRGBA c;
    const double f = best > 0.0 ? arc.utility / best : 0.0;
    c.r = static_cast<float>(1.0 - f);
    c.g = static_cast<float>(f);
    c.a = 1.0f;
    graph.points.push_back(tf2::toMsg(arc.from));
    graph.points.push_back(tf2::toMsg(arc.to));
    graph.colors.push_back(c);
    graph.colors.push_back(c);
  }
  markers.markers.push_back(graph);
  return markers;
}

PlannerMarkerPublisher::PlannerMarkerPublisher(ros::NodeHandle& nh, const std::string& topic, double roadmap_period)
    : pub_(nh.advertise<visualization_msgs::MarkerArray>(topic, 1, true)), roadmap_period_(roadmap_period) {}

void PlannerMarkerPublisher::publish(const std_msgs::Header& header, const Explorer& explorer,
                                     const Eigen::Vector4d& uav) {
  if (pub_.getNumSubscribers() == 0) return;
  const ros::WallTime wall = ros::WallTime::now();
  const bool roadmap = roadmap_wall_.isZero() || (wall - roadmap_wall_).toSec() >= roadmap_period_;
  const visualization_msgs::MarkerArray markers = plannerMarkers(header, explorer, uav, roadmap);
  for (const visualization_msgs::Marker& m : markers.markers) {
    if (m.ns == "roadmap" && !m.points.empty()) roadmap_wall_ = wall;
  }
  pub_.publish(markers);
}

surface_nbv::PlannerStatus plannerStatusMsg(const std_msgs::Header& header, const MissionProgress& progress,
                                            const Frontier& frontier, const Explorer& explorer,
                                            const ExplorerTimings& timings) {
  surface_nbv::PlannerStatus msg;
  msg.header = header;
  msg.state = progress.state;
  msg.reason = progress.reason;
  msg.message = progress.message;
  msg.ises = frontier.ises.size();
  msg.ises_inside = frontier.insideCount();
  msg.ises_remaining = frontier.remaining;
  msg.clusters = frontier.clusters.size();
  const ExplorerStats& s = explorer.stats();
  msg.tour_viewpoints = explorer.tour().size();
  msg.tour_cost = s.tour_cost;
  msg.path_length = progress.path_length;
  msg.flight_time = progress.flight_time;
  msg.blacklisted = explorer.blacklist().size();
  msg.full_recomputes = s.full_recomputes;
  msg.local_updates = s.local_updates;
  msg.legs = s.legs;
  msg.leg_failures = s.leg_failures;
  msg.graph_ms = timings.graph_ms;
  msg.tour_ms = timings.tour_ms;
  msg.path_ms = timings.path_ms;
  msg.total_ms = timings.total_ms;
  return msg;
}

void saveMissionFiles(const std::string& save_map_service, const std::string& export_mesh_service) {
  for (const auto& [service, file] : {std::make_pair(save_map_service, std::string("mission.tsdf")),
                                      std::make_pair(export_mesh_service, std::string("mission.ply"))}) {
    if (service.empty()) continue;
    surface_nbv::FilePath call;
    call.request.path = file;
    if (!ros::service::call(service, call) || call.response.code != 0) {
      ROS_WARN("nbv_planner: %s(%s) failed: %s", service.c_str(), file.c_str(), call.response.message.c_str());
    }
  }
}

}  // namespace surface_nbv
