#include "surface_nbv/sensor/triangle_mesh.h"

#include <algorithm>

namespace surface_nbv {

AlignedBox TriangleMesh::bounds() const {
  AlignedBox box;
  for (const Eigen::Vector3i& t : triangles) {
    for (int k = 0; k < 3; ++k) box.extend(vertices[t[k]].cast<double>());
  }
  return box;
}

double TriangleMesh::area() const {
  double sum = 0.0;
  for (const Eigen::Vector3i& t : triangles) {
    const Eigen::Vector3d a = vertices[t[0]].cast<double>();
    const Eigen::Vector3d b = vertices[t[1]].cast<double>();
    const Eigen::Vector3d c = vertices[t[2]].cast<double>();
    sum += 0.5 * (b - a).cross(c - a).norm();
  }
  return sum;
}

void TriangleMesh::append(const TriangleMesh& other) {
  const int base = static_cast<int>(vertices.size());
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  triangles.reserve(triangles.size() + other.triangles.size());
  for (const Eigen::Vector3i& t : other.triangles) triangles.push_back(t.array() + base);
}

void TriangleMesh::scaleAndOffset(double scale, const Eigen::Vector3d& offset) {
  for (Eigen::Vector3f& v : vertices) v = (scale * v.cast<double>() + offset).cast<float>();
}

void TriangleMesh::removeDegenerate() {
  const int n = static_cast<int>(vertices.size());
  auto bad = [&](const Eigen::Vector3i& t) {
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= n || !vertices[t[k]].allFinite()) return true;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
    const Eigen::Vector3f a = vertices[t[0]], b = vertices[t[1]], c = vertices[t[2]];
    return (b - a).cross(c - a).squaredNorm() <= 0.0f;
  };
  triangles.erase(std::remove_if(triangles.begin(), triangles.end(), bad), triangles.end());
}

}  // namespace surface_nbv
