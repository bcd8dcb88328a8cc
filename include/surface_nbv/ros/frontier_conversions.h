// Frontier (ROS-free) to surface_nbv/SurfaceFrontier and to rviz markers:
// one namespace per layer ("ises", "remaining", "viewpoints", "clusters") so
// rviz can toggle them.
#pragma once

#include <visualization_msgs/MarkerArray.h>

#include "surface_nbv/SurfaceFrontier.h"
#include "surface_nbv/surface/frontier.h"

namespace surface_nbv {

void toFrontierMsg(const Frontier& frontier, const std_msgs::Header& header, surface_nbv::SurfaceFrontier* msg);

// ISEs as cubes of `voxel_size`, C_rem in red, viewpoints as arrows (line
// segments of 1 m along the view direction), cluster members as spheres
// coloured by gain (blue low, red high).
void toFrontierMarkers(const Frontier& frontier, const std_msgs::Header& header, double voxel_size,
                       visualization_msgs::MarkerArray* markers);

}  // namespace surface_nbv
