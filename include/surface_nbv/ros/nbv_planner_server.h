// The nbv_planner node: keeps a MapMirror of tsdf/update (asking the mapper
// for a snapshot on a gap) and a CollisionMap over it, the last
// surface/frontier and the last odometry. While RUNNING, at replan_rate and
// only when a frontier arrived since the last plan (or ~replan asked), it
// builds the cluster graph (eq. 4, 5), solves the tour, plans the PRM path
// from the UAV through the first max_legs configurations of the tour and
// publishes planner/trajectory, planner/path, planner/markers and
// planner/status. A failed tour or path publishes no trajectory or path: only
// planner/status, naming the TourPlanStatus or PathStatus.
//
// Distance oracle of the cluster graph: the straight-line distance, for speed
// (the graph costs O(nodes * viewpoints) oracle calls, a PRM query each would
// cost seconds per plan); the PRM is used for the path that is flown.
//
// Services (std_srvs/Trigger, valid in any state, always answer success with
// a message): ~start (RUNNING, plans at the next tick if a frontier is held),
// ~stop (STOPPED, publishes a hold trajectory at the current pose),
// ~replan (plans at the next tick even without a new frontier).
// Inputs that are stale (older stamp than the last accepted one) or malformed
// are dropped and counted on planner/stats.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "surface_nbv/SurfaceFrontier.h"
#include "surface_nbv/planning/cluster_graph.h"
#include "surface_nbv/planning/path_planner.h"
#include "surface_nbv/ros/map_feed.h"
#include "surface_nbv/ros/planner_params.h"
#include "surface_nbv/ros/stats_reporter.h"
#include "surface_nbv/surface/frontier.h"

namespace surface_nbv {

// SurfaceFrontier to the ROS-free Frontier the planner needs: ISE positions,
// viewpoint position, yaw (from the pose's quaternion) and visible ISEs,
// clusters (viewpoints, gain) with each viewpoint's cluster set. Error, with
// `frontier` unspecified, on a non-finite value or an index out of range.
Status fromFrontierMsg(const surface_nbv::SurfaceFrontier& msg, Frontier* frontier);

// `path` (x, y, z, yaw) resampled so that consecutive points are at most
// `spacing` m apart, yaw interpolated linearly the shortest way round and
// wrapped to (-pi, pi]; the vertices are kept, consecutive duplicates dropped.
std::vector<Eigen::Vector4d> resamplePath(const std::vector<Eigen::Vector4d>& path, double spacing);

class NbvPlannerServer {
 public:
  enum class State { kStopped, kRunning };

  NbvPlannerServer(ros::NodeHandle nh, ros::NodeHandle priv, const PlannerNodeConfig& config);

 private:
  void onFrontier(const surface_nbv::SurfaceFrontierConstPtr& msg);
  void onOdometry(const nav_msgs::OdometryConstPtr& msg);
  void onTimer(const ros::WallTimerEvent&);
  bool onStart(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool onStop(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool onReplan(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);

  // One planning round; publishes the result or a failure status.
  void plan();
  void publishTrajectory(const std::vector<Eigen::Vector4d>& points, const ros::Time& stamp);
  void publishStatus(const std::string& result);
  const char* stateName() const { return state_ == State::kRunning ? "RUNNING" : "STOPPED"; }

  ros::NodeHandle nh_;
  PlannerNodeConfig config_;
  StatsReporter stats_;
  MapFeed feed_;
  PathPlanner planner_;
  ros::Subscriber frontier_sub_, odometry_sub_;
  ros::Publisher trajectory_pub_, path_pub_, status_pub_, markers_pub_;
  ros::ServiceServer start_srv_, stop_srv_, replan_srv_;
  ros::WallTimer timer_;

  State state_ = State::kStopped;
  Frontier frontier_;
  bool have_frontier_ = false;
  bool plan_pending_ = false;
  ros::Time frontier_time_;
  Eigen::Vector4d uav_ = Eigen::Vector4d::Zero();  // x, y, z, yaw
  bool have_odometry_ = false;
  ros::Time odometry_time_;
  size_t last_clusters_ = 0;
  double last_cost_ = 0.0;
  double last_ms_ = 0.0;
};

}  // namespace surface_nbv
