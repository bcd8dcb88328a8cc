// Shared scene and camera helpers for the depth renderer tests.
#pragma once

#include "surface_nbv/sim/depth_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "surface_nbv/sensor/depth_points.h"
#include "surface_nbv/sim/mesh_builder.h"
#include "surface_nbv/sim/procedural_scenes.h"
#include "surface_nbv/sim/raycast_scene.h"

namespace surface_nbv {
namespace render_test {

using Eigen::Vector3d;

// Appends the quad centre +- a +- b as two triangles.
inline void addQuad(TriangleMesh* mesh, const Vector3d& c, const Vector3d& a, const Vector3d& b) {
  const int base = static_cast<int>(mesh->vertices.size());
  const Vector3d corners[4] = {c - a - b, c + a - b, c + a + b, c - a + b};
  for (const Vector3d& p : corners) mesh->vertices.push_back(p.cast<float>());
  mesh->triangles.emplace_back(base, base + 1, base + 2);
  mesh->triangles.emplace_back(base, base + 2, base + 3);
}

// A square of half side `half` in the plane z = `z` of its frame.
inline TriangleMesh planeAtZ(double z, double half = 50.0) {
  TriangleMesh mesh;
  addQuad(&mesh, Vector3d(0, 0, z), Vector3d(half, 0, 0), Vector3d(0, half, 0));
  return mesh;
}

inline std::unique_ptr<RaycastScene> buildScene(const TriangleMesh& mesh) {
  std::unique_ptr<RaycastScene> scene;
  const Status s = RaycastScene::create(mesh, &scene);
  EXPECT_TRUE(s.ok()) << s.message();
  return scene;
}

// Optical frame at `position` with z along `forward` and x = forward x up.
inline Transform lookAlong(const Vector3d& position, const Vector3d& forward, const Vector3d& up = Vector3d::UnitZ()) {
  const Vector3d z = forward.normalized();
  const Vector3d x = z.cross(up).normalized();
  Transform T = Transform::Identity();
  T.linear().col(0) = x;
  T.linear().col(1) = z.cross(x);
  T.linear().col(2) = z;
  T.translation() = position;
  return T;
}

inline DepthImage render(const RaycastScene& scene, const CameraConfig& config, const Transform& T_W_C, int threads = 1,
                  uint64_t frame = 0) {
  const DepthRenderer renderer(scene, DepthCamera(config), threads);
  DepthImage image;
  renderer.render(T_W_C, &image, frame);
  return image;
}

// Number of pixels with |z - expected| >= tol (NaN counts as a miss).
inline size_t countOff(const DepthImage& image, double expected, double tol) {
  size_t off = 0;
  for (float z : image.data) off += (std::isfinite(z) && std::abs(z - expected) < tol) ? 0 : 1;
  return off;
}

inline CameraConfig oddCamera() {
  CameraConfig config;
  config.width = 161;
  config.height = 121;
  return config;
}

// ---- (a) a plane perpendicular to the optical axis ----

// The plane n . p = d (n unit) given in the camera frame at its identity
// pose, carried into the world by T_W_C.
struct TiltedPlane {
  Vector3d n_C = Vector3d(0.35, -0.25, -1.0).normalized();
  double d_C = n_C.dot(Vector3d(0, 0, 5));

  TriangleMesh mesh(const Transform& T_W_C) const {
    Vector3d a = n_C.cross(Vector3d::UnitX()).normalized();
    Vector3d b = n_C.cross(a);
    TriangleMesh m;
    addQuad(&m, T_W_C * (d_C * n_C), T_W_C.linear() * (20.0 * a), T_W_C.linear() * (20.0 * b));
    return m;
  }
  // Depth seen through pixel (col, row): the ray pixelRay * t meets the plane.
  double depth(const DepthCamera& cam, int col, int row) const {
    const double denom = n_C.dot(cam.pixelRay(col, row));
    return d_C / denom;
  }
};

}  // namespace render_test
}  // namespace surface_nbv
