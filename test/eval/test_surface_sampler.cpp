#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "eval_test_helpers.h"
#include "surface_nbv/eval/free_space_grid.h"
#include "surface_nbv/eval/surface_sampler.h"
#include "surface_nbv/sim/mesh_builder.h"
#include "surface_nbv/sim/procedural_scenes.h"

namespace surface_nbv {
namespace {

using Eigen::Vector3d;

TriangleMesh plantScene() {
  TriangleMesh mesh;
  EXPECT_TRUE(makeProceduralScene("plant", &mesh));
  return mesh;
}

TEST(SurfaceSampler, CountFollowsAreaAndEveryTriangleGetsItsShare) {
  const TriangleMesh mesh = plantScene();
  const double spacing = 0.2;
  SurfaceCloud cloud;
  ASSERT_TRUE(SurfaceSampler(spacing, 7).sample(mesh, 10000000, &cloud));
  const double expected = mesh.area() / (spacing * spacing);
  EXPECT_EQ(cloud.size(), static_cast<size_t>(std::ceil(expected)));
  EXPECT_EQ(cloud.size(), SurfaceSampler(spacing, 7).pointCount(mesh));
  // Stratified: each triangle holds its expected count rounded down or up.
  std::vector<int> per_triangle(mesh.numTriangles(), 0);
  for (int t : cloud.triangles) ++per_triangle[t];
  const double per_area = cloud.size() / mesh.area();
  for (size_t t = 0; t < mesh.numTriangles(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    const Vector3d a = mesh.vertices[tri[0]].cast<double>(), b = mesh.vertices[tri[1]].cast<double>(),
                   c = mesh.vertices[tri[2]].cast<double>();
    const double want = 0.5 * (b - a).cross(c - a).norm() * per_area;
    ASSERT_GE(per_triangle[t], std::floor(want) - 1.0) << "triangle " << t;
    ASSERT_LE(per_triangle[t], std::ceil(want) + 1.0) << "triangle " << t;
  }
}

TEST(SurfaceSampler, PointsLieOnTheirTriangleWithItsUnitNormal) {
  const TriangleMesh mesh = plantScene();
  SurfaceCloud cloud;
  ASSERT_TRUE(SurfaceSampler(0.5, 3).sample(mesh, 10000000, &cloud));
  ASSERT_EQ(cloud.normals.size(), cloud.size());
  ASSERT_EQ(cloud.triangles.size(), cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3i& tri = mesh.triangles[cloud.triangles[i]];
    const Vector3d a = mesh.vertices[tri[0]].cast<double>(), b = mesh.vertices[tri[1]].cast<double>(),
                   c = mesh.vertices[tri[2]].cast<double>();
    ASSERT_LT(squaredDistanceToTriangle(cloud.points[i].cast<double>(), a, b, c), 1e-10) << i;
    ASSERT_NEAR(cloud.normals[i].norm(), 1.0f, 1e-5f);
    ASSERT_GT(cloud.normals[i].cast<double>().dot((b - a).cross(c - a)), 0.0);
  }
}

TEST(SurfaceSampler, UniformOverATriangle) {
  // Halves of one triangle split by a median get equal shares.
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
  mesh.triangles = {{0, 1, 2}};
  SurfaceCloud cloud;
  ASSERT_TRUE(SurfaceSampler(0.02, 11).sample(mesh, 1000000, &cloud));
  size_t left = 0, near_corner = 0;
  for (const Eigen::Vector3f& p : cloud.points) {
    left += p.x() < p.y() ? 1 : 0;
    near_corner += p.x() + p.y() < 2.0f ? 1 : 0;  // a quarter of the area
  }
  const double n = cloud.size();
  EXPECT_NEAR(left / n, 0.5, 4.0 * std::sqrt(0.25 / n));
  EXPECT_NEAR(near_corner / n, 0.25, 4.0 * std::sqrt(0.1875 / n));
}

TEST(SurfaceSampler, RepeatsForASeedAndAnyThreadCount) {
  const TriangleMesh mesh = plantScene();
  SurfaceCloud one, two, three, other;
  ASSERT_TRUE(SurfaceSampler(0.3, 5, 1).sample(mesh, 10000000, &one));
  ASSERT_TRUE(SurfaceSampler(0.3, 5, 2).sample(mesh, 10000000, &two));
  ASSERT_TRUE(SurfaceSampler(0.3, 5, 3).sample(mesh, 10000000, &three));
  ASSERT_TRUE(SurfaceSampler(0.3, 6, 2).sample(mesh, 10000000, &other));
  EXPECT_EQ(one.points, two.points);
  EXPECT_EQ(one.points, three.points);
  EXPECT_EQ(one.normals, three.normals);
  EXPECT_EQ(one.triangles, three.triangles);
  ASSERT_EQ(one.size(), other.size());
  EXPECT_NE(one.points, other.points);
}

TEST(SurfaceSampler, RefusesTooManyPointsAndHandlesEmptyMeshes) {
  const TriangleMesh mesh = plantScene();
  SurfaceCloud cloud;
  cloud.points.resize(3);
  const Status s = SurfaceSampler(0.01, 1).sample(mesh, 1000000, &cloud);
  EXPECT_FALSE(s);
  EXPECT_NE(s.message().find("max_points"), std::string::npos) << s.message();
  EXPECT_EQ(cloud.size(), 3u);
  ASSERT_TRUE(SurfaceSampler(0.1, 1).sample(TriangleMesh(), 10, &cloud));
  EXPECT_TRUE(cloud.empty());
  // Degenerate triangles get nothing.
  TriangleMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  flat.triangles = {{0, 1, 2}, {0, 1, 3}};
  ASSERT_TRUE(SurfaceSampler(0.05, 1).sample(flat, 1000, &cloud));
  EXPECT_EQ(cloud.size(), 200u);
  for (int t : cloud.triangles) EXPECT_EQ(t, 1);
}

}  // namespace
}  // namespace surface_nbv
