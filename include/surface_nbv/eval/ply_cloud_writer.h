// Binary little-endian PLY point clouds with per-vertex colour, to inspect
// evaluation results in CloudCompare or MeshLab: x y z (float), optional
// nx ny nz (float), red green blue (uchar), optional one named float scalar.
// Written to a temporary name and renamed, so readers never see half a file.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "surface_nbv/util/status.h"

namespace surface_nbv {

using Rgb = std::array<uint8_t, 3>;

struct PlyCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;  // empty, or one per point
  std::vector<Rgb> colors;               // one per point
  std::string scalar_name;               // with `scalars`: one float property per point
  std::vector<float> scalars;
};

// Refuses mismatched sizes and names the file it cannot write.
Status writePlyCloud(const std::string& path, const PlyCloud& cloud);

}  // namespace surface_nbv
