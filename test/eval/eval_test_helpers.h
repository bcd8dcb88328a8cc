// Meshes with known geometry for the evaluation tests.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <vector>

#include "surface_nbv/eval/eval_config.h"
#include "surface_nbv/sensor/triangle_mesh.h"

namespace surface_nbv {
namespace eval_test {

using Eigen::Vector3d;

// Faces of an axis-aligned box: +x, -x, +y, -y, +z (top), -z (bottom).
constexpr int kFaces = 6;
constexpr int kBottom = 5;

inline Vector3d faceNormal(int face) {
  Vector3d n = Vector3d::Zero();
  n[face / 2] = face % 2 == 0 ? 1.0 : -1.0;
  return n;
}

// The box [lo, hi] with each face a grid of squares of about `cell` (two
// triangles each, wound outward; faces share no vertex), every vertex moved
// along its face's normal by offset(face, vertex). `face_of` gets the face of
// each triangle.
inline TriangleMesh gridBox(const Vector3d& lo, const Vector3d& hi, double cell,
                            const std::function<double(int, const Vector3d&)>& offset = nullptr,
                            std::vector<int>* face_of = nullptr) {
  TriangleMesh mesh;
  for (int face = 0; face < kFaces; ++face) {
    const int a = face / 2, b = (a + 1) % 3, c = (a + 2) % 3;
    const bool positive = face % 2 == 0;
    const int u = positive ? b : c, v = positive ? c : b;  // u x v = outward normal
    const int nu = std::max(1, static_cast<int>(std::lround((hi[u] - lo[u]) / cell)));
    const int nv = std::max(1, static_cast<int>(std::lround((hi[v] - lo[v]) / cell)));
    const int base = static_cast<int>(mesh.vertices.size());
    for (int j = 0; j <= nv; ++j) {
      for (int i = 0; i <= nu; ++i) {
        Vector3d p;
        p[a] = positive ? hi[a] : lo[a];
        p[u] = lo[u] + (hi[u] - lo[u]) * i / nu;
        p[v] = lo[v] + (hi[v] - lo[v]) * j / nv;
        if (offset) p += offset(face, p) * faceNormal(face);
        mesh.vertices.push_back(p.cast<float>());
      }
    }
    for (int j = 0; j < nv; ++j) {
      for (int i = 0; i < nu; ++i) {
        const int k = base + j * (nu + 1) + i;
        mesh.triangles.emplace_back(k, k + 1, k + nu + 2);
        mesh.triangles.emplace_back(k, k + nu + 2, k + nu + 1);
        if (face_of != nullptr) face_of->insert(face_of->end(), 2, face);
      }
    }
  }
  return mesh;
}

// The 4 m box of the `box` scene: [-2, 2] x [-2, 2] x [0, 4].
inline Vector3d boxLo() { return Vector3d(-2, -2, 0); }
inline Vector3d boxHi() { return Vector3d(2, 2, 4); }

// Mean and standard deviation, over the faces with use[face], of the offset
// field of a mesh whose vertices were moved by `offsets` (one per vertex),
// linear over each triangle: exact integrals of o and o^2 per triangle.
inline void offsetFieldStats(const TriangleMesh& mesh, const std::vector<double>& offsets,
                             const std::vector<int>& face_of, const std::vector<bool>& use, double* mean,
                             double* std_dev) {
  double area = 0.0, sum = 0.0, sum_sq = 0.0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!use[face_of[t]]) continue;
    const Eigen::Vector3i& tri = mesh.triangles[t];
    const double o0 = offsets[tri[0]], o1 = offsets[tri[1]], o2 = offsets[tri[2]];
    const Vector3d p0 = mesh.vertices[tri[0]].cast<double>(), p1 = mesh.vertices[tri[1]].cast<double>(),
                   p2 = mesh.vertices[tri[2]].cast<double>();
    const double a = 0.5 * (p1 - p0).cross(p2 - p0).norm();
    area += a;
    sum += a * (o0 + o1 + o2) / 3.0;
    sum_sq += a * (o0 * o0 + o1 * o1 + o2 * o2 + o0 * o1 + o1 * o2 + o0 * o2) / 6.0;
  }
  *mean = sum / area;
  *std_dev = std::sqrt(sum_sq / area - *mean * *mean);
}

}  // namespace eval_test
}  // namespace surface_nbv
