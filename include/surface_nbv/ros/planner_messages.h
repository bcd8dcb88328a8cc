// What nbv_planner publishes, built from the plan: the trajectory of a leg
// (planner/trajectory, planner/path), the planner/markers array and
// planner/status; and the mapper's files it asks for when the mission ends.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <std_msgs/Header.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>
#include <visualization_msgs/MarkerArray.h>

#include "surface_nbv/PlannerStatus.h"
#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/planning/mission_report.h"
#include "surface_nbv/surface/frontier.h"

namespace surface_nbv {

// The points [x, y, z, yaw] timed at `speed` along and `yaw_rate` about
// (each segment the slower of the two, at least 1 ms), velocities toward the
// next point at `speed`; `path` (if given) the same poses as a nav_msgs/Path.
trajectory_msgs::MultiDOFJointTrajectory trajectoryMsg(const std_msgs::Header& header,
                                                       const std::vector<Eigen::Vector4d>& points, double speed,
                                                       double yaw_rate, nav_msgs::Path* path = nullptr);

// The trajectory's reference for a ReferenceMonitor: each point's time from
// its start [s] and position.
std::vector<std::pair<double, Eigen::Vector3d>> trajectoryReference(
    const trajectory_msgs::MultiDOFJointTrajectory& trajectory);

// The tour from `uav`, the current leg, the next target, the blacklisted
// places and the tour's cluster-graph arcs (red: low utility f_uv, green:
// high); with `roadmap` also the roadmap's edges (at most 20,000), grey.
visualization_msgs::MarkerArray plannerMarkers(const std_msgs::Header& header, const Explorer& explorer,
                                               const Eigen::Vector4d& uav, bool roadmap);

// Publishes plannerMarkers() on a latched topic, built only while someone
// subscribes: in a headless run building them, the roadmap's edges above
// all, would only take time from the decisions. The roadmap is copied out of
// OMPL whole (bench_explorer BM_RoadmapEdges), so it goes out at most every
// `roadmap_period` wall seconds; rviz keeps a marker until one of the same
// namespace and id replaces it, and the arrays between copies leave it out
// rather than send up to 40,000 points again. An empty roadmap (nothing
// planned yet) is copied again on the next array.
class PlannerMarkerPublisher {
 public:
  PlannerMarkerPublisher(ros::NodeHandle& nh, const std::string& topic, double roadmap_period);
  void publish(const std_msgs::Header& header, const Explorer& explorer, const Eigen::Vector4d& uav);

 private:
  ros::Publisher pub_;
  double roadmap_period_;
  ros::WallTime roadmap_wall_;  // when the roadmap was last copied (0: never)
};

// planner/status: the mission's progress, the frontier's ISE and cluster
// counts, the explorer's tour and counts, and the last decision's `timings`.
surface_nbv::PlannerStatus plannerStatusMsg(const std_msgs::Header& header, const MissionProgress& progress,
                                            const Frontier& frontier, const Explorer& explorer,
                                            const ExplorerTimings& timings);

// Calls each FilePath service that is named (not empty): `save_map_service`
// with mission.tsdf, `export_mesh_service` with mission.ply (the mapper
// writes them into its out_dir). A call that fails, or is answered with a
// non-zero code, is logged as a warning; the mission's end goes on.
void saveMissionFiles(const std::string& save_map_service, const std::string& export_mesh_service);

}  // namespace surface_nbv
