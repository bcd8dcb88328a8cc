#include "surface_nbv/sim/mesh_builder.h"

#include <cmath>
#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "mesh_test_helpers.h"

namespace surface_nbv {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

using mesh_test::signedVolume;

// Every edge is used by exactly two triangles, once in each direction
// (closed, manifold and consistently wound).
bool isWatertight(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> directed;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& entry : directed) {
    if (entry.second != 1) return false;
    const auto reverse = directed.find({entry.first.second, entry.first.first});
    if (reverse == directed.end() || reverse->second != 1) return false;
  }
  return !mesh.triangles.empty();
}

// Area of a regular n-gon inscribed in a circle of radius r.
double polygonArea(double r, int n) { return 0.5 * n * r * r * std::sin(2.0 * M_PI / n); }

void expectBounds(const TriangleMesh& mesh, const Vector3d& lo, const Vector3d& hi, double tol) {
  const AlignedBox box = mesh.bounds();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(box.min[k], lo[k], tol) << "axis " << k;
    EXPECT_NEAR(box.max[k], hi[k], tol) << "axis " << k;
  }
}

TEST(MeshBuilder, BoxAreaBoundsVolumeExact) {
  MeshBuilder b;
  const double s = 3.0;
  b.addBox(Vector3d(1, -2, 0.5), Vector3d(s, s, s));
  const TriangleMesh& m = b.mesh();
  EXPECT_EQ(m.numTriangles(), 12u);
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_DOUBLE_EQ(m.area(), 6.0 * s * s);
  const AlignedBox box = m.bounds();
  EXPECT_EQ(box.min, Vector3d(-0.5, -3.5, -1.0));
  EXPECT_EQ(box.max, Vector3d(2.5, -0.5, 2.0));
  EXPECT_NEAR(signedVolume(m), s * s * s, 1e-9);
  EXPECT_TRUE(isWatertight(m));
}

TEST(MeshBuilder, AlignedBoxKeepsExactCornersInEitherOrder) {
  MeshBuilder b;
  b.addAlignedBox(Vector3d(-32.1, 3.0, 11.7), Vector3d(-32.5, -4.0, 0.0));
  // Exact up to the float storage of the vertices.
  const Vector3d lo = Vector3d(-32.5, -4.0, 0.0).cast<float>().cast<double>();
  const Vector3d hi = Vector3d(-32.1, 3.0, 11.7).cast<float>().cast<double>();
  expectBounds(b.mesh(), lo, hi, 0.0);
  EXPECT_NEAR(signedVolume(b.mesh()), 0.4 * 7.0 * 11.7, 1e-3);
  EXPECT_TRUE(isWatertight(b.mesh()));
}

TEST(MeshBuilder, YawedBoxKeepsVolumeAndRotatesBounds) {
  MeshBuilder b;
  b.addBox(Vector3d(0, 0, 1), Vector3d(2, 2, 2), M_PI / 4.0);
  EXPECT_NEAR(signedVolume(b.mesh()), 8.0, 1e-5);
  EXPECT_NEAR(b.mesh().area(), 24.0, 1e-5);
  expectBounds(b.mesh(), Vector3d(-std::sqrt(2.0), -std::sqrt(2.0), 0),
               Vector3d(std::sqrt(2.0), std::sqrt(2.0), 2), 1e-6);
  EXPECT_TRUE(isWatertight(b.mesh()));
}

TEST(MeshBuilder, OrientedBoxOutwardEvenForReflection) {
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  MeshBuilder b;
  b.addOrientedBox(Vector3d(5, 6, 7), Vector3d(0.5, 1.0, 2.0), r);
  EXPECT_NEAR(signedVolume(b.mesh()), 8.0 * 0.5 * 1.0 * 2.0, 1e-4);
  EXPECT_TRUE(isWatertight(b.mesh()));

  MeshBuilder mirrored;
  mirrored.addOrientedBox(Vector3d(5, 6, 7), Vector3d(0.5, 1.0, 2.0),
                          r * Vector3d(1, -1, 1).asDiagonal());
  EXPECT_NEAR(signedVolume(mirrored.mesh()), 8.0, 1e-4);
  EXPECT_TRUE(isWatertight(mirrored.mesh()));
}

TEST(MeshBuilder, BeamSpansEndpoints) {
  MeshBuilder b;
  b.addBeam(Vector3d(0, 0, 5), Vector3d(10, 0, 5), 0.3, 0.5);
  expectBounds(b.mesh(), Vector3d(0, -0.15, 4.75), Vector3d(10, 0.15, 5.25), 1e-6);
  EXPECT_NEAR(signedVolume(b.mesh()), 10 * 0.3 * 0.5, 1e-5);
  EXPECT_TRUE(isWatertight(b.mesh()));

  MeshBuilder vertical;
  vertical.addBeam(Vector3d(1, 1, 0), Vector3d(1, 1, 8), 0.3, 0.3);
  expectBounds(vertical.mesh(), Vector3d(0.85, 0.85, 0), Vector3d(1.15, 1.15, 8), 1e-6);
  EXPECT_NEAR(signedVolume(vertical.mesh()), 8 * 0.09, 1e-5);

  MeshBuilder slanted;
  const Vector3d p0(1, 2, 3), p1(4, -2, 9);
  slanted.addBeam(p0, p1, 1.0, 0.8);
  EXPECT_NEAR(signedVolume(slanted.mesh()), (p1 - p0).norm() * 0.8, 1e-4);
  EXPECT_TRUE(isWatertight(slanted.mesh()));

  MeshBuilder empty;
  empty.addBeam(p0, p0, 1.0, 1.0);
  EXPECT_TRUE(empty.mesh().empty());
}

TEST(MeshBuilder, CylinderVolumeMatchesPolygonAndApproachesCircle) {
  const double r = 1.5, h = 4.0;
  for (int n : {3, 8, 32}) {
    MeshBuilder b;
    b.addCylinder(Vector3d(0, 0, 0), Vector3d(0, 0, h), r, n);
    const double v = signedVolume(b.mesh());
    EXPECT_NEAR(v, polygonArea(r, n) * h, 1e-4) << n;
    // The inscribed polygon loses at most this fraction of the disc area.
    const double loss = 1.0 - std::sin(2.0 * M_PI / n) / (2.0 * M_PI / n);
    EXPECT_LE(v, M_PI * r * r * h);
    EXPECT_GE(v, M_PI * r * r * h * (1.0 - loss) - 1e-4);
    EXPECT_TRUE(isWatertight(b.mesh())) << n;
    EXPECT_EQ(b.mesh().numTriangles(), size_t(4 * n));
  }
  MeshBuilder b32;
  b32.addCylinder(Vector3d(0, 0, 0), Vector3d(0, 0, h), r, 32);
  EXPECT_NEAR(signedVolume(b32.mesh()) / (M_PI * r * r * h), 1.0, 0.007);
}

TEST(MeshBuilder, CylinderAlongArbitraryAxis) {
  const Vector3d base(1, -2, 3), top(-3, 4, 0.5);
  MeshBuilder b;
  b.addCylinder(base, top, 0.7, 24);
  EXPECT_NEAR(signedVolume(b.mesh()), polygonArea(0.7, 24) * (top - base).norm(), 1e-4);
  EXPECT_TRUE(isWatertight(b.mesh()));
  for (const Eigen::Vector3f& p : b.mesh().vertices) {
    const Vector3d q = p.cast<double>() - base;
    const Vector3d axis = (top - base).normalized();
    const double radial = (q - q.dot(axis) * axis).norm();
    EXPECT_TRUE(std::abs(radial - 0.7) < 1e-5 || radial < 1e-5) << radial;
  }
}

TEST(MeshBuilder, UncappedCylinderIsOpenTube) {
  MeshBuilder b;
  b.addCylinder(Vector3d(0, 0, 0), Vector3d(0, 0, 2), 1.0, 16, false);
  EXPECT_EQ(b.mesh().numTriangles(), 32u);
  EXPECT_FALSE(isWatertight(b.mesh()));
  EXPECT_NEAR(b.mesh().area(), 16 * 2.0 * 2.0 * std::sin(M_PI / 16), 1e-4);
}

TEST(MeshBuilder, FrustumAndConeVolumes) {
  const int n = 32;
  const double h = 3.0, r0 = 2.0, r1 = 1.0;
  const double a0 = polygonArea(r0, n), a1 = polygonArea(r1, n);
  MeshBuilder f;
  f.addFrustum(Vector3d(0, 0, 0), Vector3d(0, 0, h), r0, r1, n);
  EXPECT_NEAR(signedVolume(f.mesh()), h / 3.0 * (a0 + a1 + std::sqrt(a0 * a1)), 1e-4);
  EXPECT_TRUE(isWatertight(f.mesh()));

  MeshBuilder c;
  c.addCone(Vector3d(0, 0, 1), Vector3d(0, 0, 1 + h), r0, n);
  EXPECT_NEAR(signedVolume(c.mesh()), a0 * h / 3.0, 1e-4);
  EXPECT_NEAR(signedVolume(c.mesh()) / (M_PI * r0 * r0 * h / 3.0), 1.0, 0.007);
  EXPECT_TRUE(isWatertight(c.mesh()));
  EXPECT_EQ(c.mesh().numTriangles(), size_t(2 * n));
  EXPECT_NEAR(c.mesh().bounds().max.z(), 1 + h, 1e-6);

  MeshBuilder inverted;
  inverted.addFrustum(Vector3d(0, 0, 0), Vector3d(0, 0, h), 0.0, r0, n);
  EXPECT_NEAR(signedVolume(inverted.mesh()), a0 * h / 3.0, 1e-4);
  EXPECT_TRUE(isWatertight(inverted.mesh()));
}

TEST(MeshBuilder, SphereVerticesOnSurfaceAndVolumeClose) {
  const Vector3d c(1, 2, 3);
  const double r = 2.5;
  MeshBuilder b;
  b.addSphere(c, r, 24, 48);
  const TriangleMesh& m = b.mesh();
  EXPECT_EQ(m.numTriangles(), size_t(2 * 48 * (24 - 1)));
  for (const Eigen::Vector3f& p : m.vertices) {
    EXPECT_NEAR((p.cast<double>() - c).norm(), r, 1e-5 * r);
  }
  const double exact = 4.0 / 3.0 * M_PI * r * r * r;
  const double v = signedVolume(m);
  EXPECT_LT(v, exact);
  EXPECT_GT(v, 0.985 * exact);
  EXPECT_TRUE(isWatertight(m));
  expectBounds(m, c.array() - r, c.array() + r, 1e-5);
}

TEST(MeshBuilder, SphereCoarseLimits) {
  MeshBuilder b;
  b.addSphere(Vector3d::Zero(), 1.0, 1, 2);
  EXPECT_EQ(b.mesh().numTriangles(), size_t(2 * 3 * (2 - 1)));
  EXPECT_TRUE(isWatertight(b.mesh()));
  EXPECT_GT(signedVolume(b.mesh()), 0.0);
}

TEST(MeshBuilder, PrismConvexAndNonConvex) {
  MeshBuilder square;
  square.addPrism({{0, 0}, {2, 0}, {2, 2}, {0, 2}}, 1.0, 4.0);
  EXPECT_NEAR(signedVolume(square.mesh()), 12.0, 1e-5);
  EXPECT_TRUE(isWatertight(square.mesh()));
  expectBounds(square.mesh(), Vector3d(0, 0, 1), Vector3d(2, 2, 4), 0.0);

  // An L shape given clockwise, with a collinear and a repeated point.
  const std::vector<Vector2d> l_shape = {{0, 0}, {0, 3}, {1, 3}, {1, 1}, {2, 1},
                                         {3, 1}, {3, 0}, {3, 0}};
  MeshBuilder l;
  l.addPrism(l_shape, 2.0, 0.0);
  EXPECT_NEAR(signedVolume(l.mesh()), 2.0 * 5.0, 1e-5);
  EXPECT_NEAR(l.mesh().area(), 2 * 5.0 + 2.0 * 12.0, 1e-5);
  EXPECT_TRUE(isWatertight(l.mesh()));

  MeshBuilder degenerate;
  degenerate.addPrism({{0, 0}, {1, 1}, {2, 2}}, 0.0, 1.0);
  degenerate.addPrism({{0, 0}, {1, 0}}, 0.0, 1.0);
  EXPECT_TRUE(degenerate.mesh().empty());
}

TEST(MeshBuilder, TriangulationOfNonConvexPolygonCoversItsArea) {
  // A comb with three teeth: area 5 x 1 base + 3 teeth of 1 x 2.
  const std::vector<Vector2d> comb = {{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1},
                                      {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  const std::vector<Eigen::Vector3i> tris = triangulatePolygon(comb);
  ASSERT_EQ(tris.size(), comb.size() - 2);
  double area = 0.0;
  for (const Eigen::Vector3i& t : tris) {
    const Vector2d e1 = comb[t[1]] - comb[t[0]], e2 = comb[t[2]] - comb[t[0]];
    const double a = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    EXPECT_GT(a, 0.0);
    area += a;
  }
  EXPECT_NEAR(area, 5.0 + 6.0, 1e-12);
}

TEST(MeshBuilder, InwardAndFlippedReverseWinding) {
  MeshBuilder b;
  b.setInward(true);
  EXPECT_TRUE(b.inward());
  b.addBox(Vector3d(0, 0, 0), Vector3d(2, 3, 4));
  EXPECT_NEAR(signedVolume(b.mesh()), -24.0, 1e-6);
  b.setInward(false);
  b.addSphere(Vector3d(10, 0, 0), 1.0, 12, 24);
  const double sphere = signedVolume(b.mesh()) + 24.0;
  EXPECT_GT(sphere, 0.0);
  EXPECT_TRUE(isWatertight(b.mesh()));

  const TriangleMesh flipped = b.flipped();
  EXPECT_NEAR(signedVolume(flipped), -signedVolume(b.mesh()), 1e-9);
  EXPECT_TRUE(isWatertight(flipped));
  EXPECT_EQ(flipped.numTriangles(), b.mesh().numTriangles());
}

TEST(MeshBuilder, VolumesAddAcrossPrimitivesAndTakeEmpties) {
  MeshBuilder b;
  b.addBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  b.addBox(Vector3d(5, 0, 0), Vector3d(2, 2, 2));
  b.addCylinder(Vector3d(-5, 0, 0), Vector3d(-5, 0, 2), 1.0, 16);
  EXPECT_NEAR(signedVolume(b.mesh()), 1.0 + 8.0 + 2.0 * polygonArea(1.0, 16), 1e-4);
  EXPECT_TRUE(isWatertight(b.mesh()));
  const size_t n = b.mesh().numTriangles();
  const TriangleMesh taken = b.take();
  EXPECT_EQ(taken.numTriangles(), n);
  EXPECT_TRUE(b.mesh().empty());
  EXPECT_TRUE(b.mesh().vertices.empty());
}

}  // namespace
}  // namespace surface_nbv
