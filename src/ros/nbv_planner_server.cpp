#include "surface_nbv/ros/nbv_planner_server.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <nav_msgs/Path.h>
#include <std_msgs/String.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>


namespace surface_nbv {
namespace {

double wrapAngle(double a) {
  a = std::remainder(a, 2.0 * M_PI);
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

double yawOf(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

bool finite(const geometry_msgs::Point& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

bool finite(const geometry_msgs::Quaternion& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w) &&
         q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w > 1e-12;
}

geometry_msgs::Quaternion yawQuaternion(double yaw) {
  geometry_msgs::Quaternion q;
  q.w = std::cos(0.5 * yaw);
  q.z = std::sin(0.5 * yaw);
  return q;
}

visualization_msgs::Marker lineStrip(const std_msgs::Header& header, const std::string& ns,
                                     const std::vector<Eigen::Vector4d>& points, float r, float g, float b) {
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = ns;
  m.id = 0;
  m.type = visualization_msgs::Marker::LINE_STRIP;
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

Status fromFrontierMsg(const surface_nbv::SurfaceFrontier& msg, Frontier* frontier) {
  *frontier = Frontier();
  frontier->ises.resize(msg.ises.size());
  for (size_t i = 0; i < msg.ises.size(); ++i) {
    if (!finite(msg.ises[i])) return Status::Error("ise " + std::to_string(i) + " is not finite");
    frontier->ises[i].position = Eigen::Vector3d(msg.ises[i].x, msg.ises[i].y, msg.ises[i].z);
  }
  for (uint32_t r : msg.remaining) {
    if (r >= msg.ises.size()) return Status::Error("remaining index " + std::to_string(r) + " out of range");
    frontier->ises[r].remaining = true;
  }
  frontier->remaining = msg.remaining.size();
  frontier->scanned = msg.num_scanned;
  frontier->viewpoints.resize(msg.viewpoints.size());
  for (size_t i = 0; i < msg.viewpoints.size(); ++i) {
    const surface_nbv::FrontierViewpoint& in = msg.viewpoints[i];
    if (!finite(in.pose.position) || !finite(in.pose.orientation)) {
      return Status::Error("viewpoint " + std::to_string(i) + " has a non-finite pose");
    }
    Viewpoint& v = frontier->viewpoints[i];
    v.position = Eigen::Vector3d(in.pose.position.x, in.pose.position.y, in.pose.position.z);
    v.yaw = yawOf(in.pose.orientation);
    v.view_direction = Eigen::Vector3d(std::cos(v.yaw), std::sin(v.yaw), 0.0);
    for (uint32_t k : in.visible_ises) {
      if (k >= msg.ises.size()) return Status::Error("viewpoint " + std::to_string(i) + " sees ISE out of range");
    }
    v.visible.assign(in.visible_ises.begin(), in.visible_ises.end());
  }
  frontier->clusters.resize(msg.clusters.size());
  for (size_t c = 0; c < msg.clusters.size(); ++c) {
    const surface_nbv::FrontierCluster& in = msg.clusters[c];
    if (in.viewpoints.empty()) return Status::Error("cluster " + std::to_string(c) + " is empty");
    if (!std::isfinite(in.gain) || in.gain < 0.0) return Status::Error("cluster " + std::to_string(c) + " gain");
    for (uint32_t k : in.viewpoints) {
      if (k >= msg.viewpoints.size()) {
        return Status::Error("cluster " + std::to_string(c) + " viewpoint index out of range");
      }
      if (frontier->viewpoints[k].cluster >= 0) {
        return Status::Error("viewpoint " + std::to_string(k) + " is in two clusters");
      }
      frontier->viewpoints[k].cluster = static_cast<int32_t>(c);
    }
    frontier->clusters[c].viewpoints.assign(in.viewpoints.begin(), in.viewpoints.end());
    frontier->clusters[c].gain = in.gain;
  }
  return Status::Ok();
}

std::vector<Eigen::Vector4d> resamplePath(const std::vector<Eigen::Vector4d>& path, double spacing) {
  std::vector<Eigen::Vector4d> out;
  for (const Eigen::Vector4d& q : path) {
    Eigen::Vector4d p = q;
    p.w() = wrapAngle(p.w());
    if (out.empty()) {
      out.push_back(p);
      continue;
    }
    const Eigen::Vector4d a = out.back();
    const double length = (p.head<3>() - a.head<3>()).norm();
    const double dyaw = wrapAngle(p.w() - a.w());
    if (length < 1e-9 && std::abs(dyaw) < 1e-9) continue;
    const int steps = std::max(1, static_cast<int>(std::ceil(length / spacing)));
    for (int s = 1; s <= steps; ++s) {
      const double t = static_cast<double>(s) / steps;
      Eigen::Vector4d r;
      r.head<3>() = a.head<3>() + t * (p.head<3>() - a.head<3>());
      r.w() = wrapAngle(a.w() + t * dyaw);
      out.push_back(r);
    }
  }
  return out;
}

NbvPlannerServer::NbvPlannerServer(ros::NodeHandle nh, ros::NodeHandle priv, const PlannerNodeConfig& config)
    : nh_(nh),
      config_(config),
      stats_(nh_, "planner/stats", "nbv_planner", config.stats_period),
      feed_(nh_, config.map, config.collision, config.snapshot_service, "nbv_planner", &stats_),
      planner_(config.path) {
  if (Status s = planner_.setMap(&feed_.collision(), config_.map.bounds); !s) {
    ROS_ERROR("nbv_planner: path planner refused the map: %s", s.message().c_str());
  }
  state_ = config_.start_running ? State::kRunning : State::kStopped;
  frontier_sub_ = nh_.subscribe("surface/frontier", 2, &NbvPlannerServer::onFrontier, this);
  odometry_sub_ = nh_.subscribe("odometry", 20, &NbvPlannerServer::onOdometry, this);
  trajectory_pub_ = nh_.advertise<trajectory_msgs::MultiDOFJointTrajectory>("planner/trajectory", 1, true);
  path_pub_ = nh_.advertise<nav_msgs::Path>("planner/path", 1, true);
  status_pub_ = nh_.advertise<std_msgs::String>("planner/status", 1, true);
  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("planner/markers", 1, true);
  start_srv_ = priv.advertiseService("start", &NbvPlannerServer::onStart, this);
  stop_srv_ = priv.advertiseService("stop", &NbvPlannerServer::onStop, this);
  replan_srv_ = priv.advertiseService("replan", &NbvPlannerServer::onReplan, this);
  timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / config_.replan_rate), &NbvPlannerServer::onTimer, this);
  ROS_INFO("nbv_planner: %s, replan %.1f Hz, speed %.2f m/s, collision radius %.1f m, lambda_tc %.3f, lambda_ic %.3f",
           stateName(), config_.replan_rate, config_.speed, config_.path.collision_radius, config_.graph.lambda_tc,
           config_.graph.lambda_ic);
  publishStatus("waiting");
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
  have_frontier_ = true;
  plan_pending_ = true;
  stats_.count("frontiers");
}

void NbvPlannerServer::onOdometry(const nav_msgs::OdometryConstPtr& msg) {
  if (have_odometry_ && msg->header.stamp < odometry_time_) {
    stats_.count("odometry_stale");
    return;
  }
  const geometry_msgs::Pose& pose = msg->pose.pose;
  if (!finite(pose.position) || !finite(pose.orientation)) {
    stats_.count("odometry_malformed");
    return;
  }
  if (msg->header.frame_id != config_.world_frame) {
    stats_.count("odometry_wrong_frame");
    ROS_WARN_THROTTLE(5.0, "nbv_planner: odometry in frame '%s', expected '%s'", msg->header.frame_id.c_str(),
                      config_.world_frame.c_str());
    return;
  }
  uav_ = Eigen::Vector4d(pose.position.x, pose.position.y, pose.position.z, yawOf(pose.orientation));
  odometry_time_ = msg->header.stamp;
  have_odometry_ = true;
}

void NbvPlannerServer::onTimer(const ros::WallTimerEvent&) {
  if (state_ != State::kRunning || !plan_pending_) return;
  if (!feed_.mirror().synced() || !have_odometry_ || !have_frontier_) {
    publishStatus(!feed_.mirror().synced() ? "waiting for the map" : !have_odometry_ ? "waiting for odometry"
                                                                                : "waiting for a frontier");
    return;
  }
  plan_pending_ = false;
  if (feed_.refresh() != MapFeed::Refresh::kUnchanged) planner_.mapChanged();
  plan();
}

void NbvPlannerServer::plan() {
  const auto t0 = std::chrono::steady_clock::now();
  const DistanceFn euclidean = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm(); };
  const ClusterGraph graph(frontier_, uav_, euclidean, config_.graph);
  const TourPlan tour = planTour(graph);
  last_clusters_ = frontier_.clusters.size();
  auto elapsedMs = [&t0] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  };
  if (tour.status != TourPlanStatus::kOk || tour.configurations.empty()) {
    last_ms_ = elapsedMs();
    stats_.count(std::string("tour_") + toString(tour.status));
    ROS_WARN_THROTTLE(5.0, "nbv_planner: no tour (%s) %s", toString(tour.status), tour.message.c_str());
    publishStatus(std::string("tour failed: ") + toString(tour.status));
    return;
  }
  last_cost_ = tour.cost;

  // Legs: UAV -> the first configuration a path reaches, then on to the next
  // ones while their paths succeed, at most max_legs in all.
  std::vector<Eigen::Vector4d> path{uav_};
  std::vector<Eigen::Vector4d> reached{uav_};
  PathStatus first_failure = PathStatus::kExactSolution;
  for (const Eigen::Vector4d& goal : tour.configurations) {
    if (static_cast<int>(reached.size()) > config_.max_legs) break;
    const PathResult leg = planner_.plan(reached.back(), goal);
    if (!hasPath(leg.status)) {
      stats_.count(std::string("path_") + toString(leg.status));
      if (reached.size() > 1) break;
      if (first_failure == PathStatus::kExactSolution) first_failure = leg.status;
      continue;
    }
    path.insert(path.end(), leg.path.begin() + (leg.path.empty() ? 0 : 1), leg.path.end());
    reached.push_back(goal);
  }
  last_ms_ = elapsedMs();
  stats_.recordMs(last_ms_);
  if (reached.size() == 1) {
    ROS_WARN_THROTTLE(5.0, "nbv_planner: no path to any tour configuration (first failure %s)",
                      toString(first_failure));
    publishStatus(std::string("path failed: ") + toString(first_failure));
    return;
  }
  stats_.count("plans");
  publishTrajectory(resamplePath(path, config_.trajectory_spacing), odometry_time_);
  std_msgs::Header header;
  header.stamp = odometry_time_;
  header.frame_id = config_.world_frame;
  visualization_msgs::MarkerArray markers;
  std::vector<Eigen::Vector4d> tour_line{uav_};
  tour_line.insert(tour_line.end(), tour.configurations.begin(), tour.configurations.end());
  markers.markers.push_back(lineStrip(header, "tour", tour_line, 1.0f, 0.6f, 0.0f));
  markers.markers.push_back(lineStrip(header, "path", path, 0.0f, 0.8f, 0.2f));
  markers_pub_.publish(markers);
  publishStatus("planned " + std::to_string(reached.size() - 1) + " leg(s), " +
                std::to_string(tour.viewpoints.size()) + " tour viewpoints");
}

void NbvPlannerServer::publishTrajectory(const std::vector<Eigen::Vector4d>& points, const ros::Time& stamp) {
  trajectory_msgs::MultiDOFJointTrajectory trajectory;
  trajectory.header.stamp = stamp;
  trajectory.header.frame_id = config_.world_frame;
  trajectory.joint_names = {"base_link"};
  nav_msgs::Path path;
  path.header = trajectory.header;
  double t = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector4d& p = points[i];
    if (i > 0) {
      const Eigen::Vector4d& a = points[i - 1];
      const double dt = std::max((p.head<3>() - a.head<3>()).norm() / config_.speed,
                                 std::abs(wrapAngle(p.w() - a.w())) / config_.yaw_rate);
      t += std::max(dt, 1e-3);
    }
    trajectory_msgs::MultiDOFJointTrajectoryPoint point;
    geometry_msgs::Transform tf;
    tf.translation.x = p.x();
    tf.translation.y = p.y();
    tf.translation.z = p.z();
    tf.rotation = yawQuaternion(p.w());
    point.transforms.push_back(tf);
    point.time_from_start = ros::Duration(t);
    trajectory.points.push_back(point);
    geometry_msgs::PoseStamped pose;
    pose.header = trajectory.header;
    pose.pose.position = tf2::toMsg(Eigen::Vector3d(p.head<3>()));
    pose.pose.orientation = tf.rotation;
    path.poses.push_back(pose);
  }
  trajectory_pub_.publish(trajectory);
  path_pub_.publish(path);
}

void NbvPlannerServer::publishStatus(const std::string& result) {
  char line[256];
  std::snprintf(line, sizeof(line), "state=%s ises=%zu clusters=%zu tour_cost=%.3f planning_ms=%.1f result=",
                stateName(), frontier_.ises.size(), last_clusters_, last_cost_, last_ms_);
  std_msgs::String msg;
  msg.data = line + result;
  status_pub_.publish(msg);
}

bool NbvPlannerServer::onStart(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  const bool was_running = state_ == State::kRunning;
  state_ = State::kRunning;
  plan_pending_ = have_frontier_ || plan_pending_;
  res.success = true;
  res.message = was_running ? "already running" : "running";
  publishStatus(res.message);
  return true;
}

bool NbvPlannerServer::onStop(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  state_ = State::kStopped;
  res.success = true;
  if (have_odometry_) {
    publishTrajectory({uav_}, odometry_time_);
    res.message = "stopped; holding the current pose";
  } else {
    res.message = "stopped; no odometry yet, no hold trajectory sent";
  }
  publishStatus(res.message);
  return true;
}

bool NbvPlannerServer::onReplan(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  plan_pending_ = true;
  res.success = true;
  res.message = state_ == State::kRunning ? "replanning at the next tick" : "replan queued until ~start";
  return true;
}

}  // namespace surface_nbv
