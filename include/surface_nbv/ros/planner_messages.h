// What nbv_planner publishes, built from the plan: the trajectory of a leg
// (planner/trajectory, planner/path) and the planner/markers array.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <nav_msgs/Path.h>
#include <std_msgs/Header.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>
#include <visualization_msgs/MarkerArray.h>

#include "surface_nbv/planning/explorer.h"

namespace surface_nbv {

// The points [x, y, z, yaw] timed at `speed` along and `yaw_rate` about
// (each segment the slower of the two, at least 1 ms), velocities toward the
// next point at `speed`; `path` (if given) the same poses as a nav_msgs/Path.
trajectory_msgs::MultiDOFJointTrajectory trajectoryMsg(const std_msgs::Header& header,
                                                       const std::vector<Eigen::Vector4d>& points, double speed,
                                                       double yaw_rate, nav_msgs::Path* path = nullptr);

// The tour from `uav`, the current leg, the next target, the blacklisted
// places and the tour's cluster-graph arcs (red: low utility f_uv, green:
// high); with `roadmap` also the roadmap's edges (at most 20,000), grey.
visualization_msgs::MarkerArray plannerMarkers(const std_msgs::Header& header, const Explorer& explorer,
                                               const Eigen::Vector4d& uav, bool roadmap);

}  // namespace surface_nbv
