// An indexed triangle mesh in metres, in whatever frame its producer states
// (scenes are in the world frame, Z up). Triangles index into `vertices` and
// are wound counter-clockwise seen from outside for closed procedural meshes.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "surface_nbv/common.h"

namespace surface_nbv {

struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;

  bool empty() const { return triangles.empty(); }
  size_t numTriangles() const { return triangles.size(); }

  // Bounds of the vertices used by triangles (empty box for an empty mesh).
  AlignedBox bounds() const;
  // Sum of triangle areas in m^2.
  double area() const;
  // Appends `other`, re-indexing its triangles.
  void append(const TriangleMesh& other);
  // Applies p' = scale * p + offset to every vertex.
  void scaleAndOffset(double scale, const Eigen::Vector3d& offset);
  // Drops triangles with a repeated index, a non-finite vertex or zero area.
  void removeDegenerate();
};

}  // namespace surface_nbv
