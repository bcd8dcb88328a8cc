#include "surface_nbv/sensor/depth_points.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {

bool depthToPoints(const DepthCamera& camera, const DepthImage& depth, std::vector<Eigen::Vector3f>* points_C,
                   int stride) {
  points_C->clear();
  if (depth.width != camera.width() || depth.height != camera.height()) return false;
  stride = std::max(1, stride);
  for (int row = 0; row < depth.height; row += stride) {
    for (int col = 0; col < depth.width; col += stride) {
      const float z = depth.at(row, col);
      if (!std::isfinite(z)) continue;
      points_C->push_back((camera.pixelRay(col, row) * z).cast<float>());
    }
  }
  return true;
}

}  // namespace surface_nbv
