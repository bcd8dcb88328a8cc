// Where the depth camera sits on the UAV: the optical frame in base_link, and
// the level body pose the planner and the simulator fly.
#pragma once

#include <Eigen/Core>

#include "surface_nbv/common.h"
#include "surface_nbv/sensor/depth_camera.h"

namespace surface_nbv {

// Camera optical frame (z forward, x right, y down) on a forward-facing mount
// at `offset` in base_link, pitched `pitch_deg` down about the body's y axis
// (CameraConfig::pitch_deg; 0 is level).
Transform opticalInBody(const Eigen::Vector3d& offset = Eigen::Vector3d::Zero(), double pitch_deg = 0.0);
// The same at the origin of base_link, for a camera's config.
Transform opticalInBody(const CameraConfig& camera);

// T_W_B of a level base_link at p_W turned by yaw about world z.
Transform levelBodyPose(const Eigen::Vector3d& p_W, double yaw);

}  // namespace surface_nbv
