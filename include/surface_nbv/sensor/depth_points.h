// Back-projection of a depth image into a point cloud in the optical frame.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sensor/depth_image.h"

namespace surface_nbv {

// Appends one point per finite pixel (every `stride`-th row and column) to
// `points_C`, which is cleared first. Returns false if the image size does not
// match the camera.
bool depthToPoints(const DepthCamera& camera, const DepthImage& depth, std::vector<Eigen::Vector3f>* points_C,
                   int stride = 1);

}  // namespace surface_nbv
