// Dense, seeded, area-uniform point samples of a triangle mesh, with the unit
// normal of the triangle each point lies on (orientation from the winding).
// Sampling is stratified over the cumulated triangle areas: each triangle
// gets its expected count rounded up or down, so no area is left unsampled
// by chance. Points are in the mesh's frame (metres), float like the mesh.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct SurfaceCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;  // unit
  std::vector<int> triangles;            // index of the source triangle

  size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
};

class SurfaceSampler {
 public:
  // `spacing` > 0: the cloud holds ceil(area / spacing^2) points.
  SurfaceSampler(double spacing, uint64_t seed, int threads = 1);

  // Refuses (and leaves `cloud` alone) when more than `max_points` would be drawn.
  Status sample(const TriangleMesh& mesh, size_t max_points, SurfaceCloud* cloud) const;
  // How many points `mesh` gets.
  size_t pointCount(const TriangleMesh& mesh) const;

 private:
  double spacing_;
  uint64_t seed_;
  int threads_;
};

}  // namespace surface_nbv
