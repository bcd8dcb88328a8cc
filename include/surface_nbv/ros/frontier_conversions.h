// Frontier (ROS-free) to surface_nbv/SurfaceFrontier and to rviz markers:
// one namespace per layer ("ises", "remaining", "viewpoints", "clusters") so
// rviz can toggle them; SurfaceFrontier back to Frontier for the planner, the
// planner's path resampling, and the pose checks they share with it.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <geometry_msgs/Point.h>
#include <geometry_msgs/Quaternion.h>
#include <visualization_msgs/MarkerArray.h>

#include "surface_nbv/SurfaceFrontier.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// Yaw [rad] of a quaternion (rotation about z; it need not be normalised).
double yawOf(const geometry_msgs::Quaternion& q);

// All coordinates finite.
bool allFinite(const geometry_msgs::Point& p);
// All components finite and not the zero quaternion.
bool allFinite(const geometry_msgs::Quaternion& q);

// SurfaceFrontier to the ROS-free Frontier the planner needs: ISE positions,
// viewpoint position, yaw (from the pose's quaternion) and visible ISEs,
// clusters (viewpoints, gain) with each viewpoint's cluster set. Error, with
// `frontier` unspecified, on a non-finite value or an index out of range.
Status fromFrontierMsg(const surface_nbv::SurfaceFrontier& msg, Frontier* frontier);

// `path` (x, y, z, yaw) resampled so that consecutive points are at most
// `spacing` m apart, yaw interpolated linearly the shortest way round and
// wrapped to (-pi, pi]; the vertices are kept, consecutive duplicates dropped.
std::vector<Eigen::Vector4d> resamplePath(const std::vector<Eigen::Vector4d>& path, double spacing);

void toFrontierMsg(const Frontier& frontier, const std_msgs::Header& header, surface_nbv::SurfaceFrontier* msg);

// ISEs as cubes of `voxel_size`, C_rem in red, viewpoints as arrows (line
// segments of 1 m along the view direction), cluster members as spheres
// coloured by gain (blue low, red high).
void toFrontierMarkers(const Frontier& frontier, const std_msgs::Header& header, double voxel_size,
                       visualization_msgs::MarkerArray* markers);

}  // namespace surface_nbv
