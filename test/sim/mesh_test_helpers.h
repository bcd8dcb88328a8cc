// Shared measures of triangle meshes for the mesh tests.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "surface_nbv/sensor/triangle_mesh.h"

namespace surface_nbv {
namespace mesh_test {

// Divergence theorem: positive for outward normals, negative for inward.
inline double signedVolume(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.vertices[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.vertices[t[2]].cast<double>();
    sum += a.dot(b.cross(c)) / 6.0;
  }
  return sum;
}

}  // namespace mesh_test
}  // namespace surface_nbv
