#include "surface_nbv/sim/procedural_scenes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "mesh_test_helpers.h"

namespace surface_nbv {
namespace {

using Eigen::Vector3d;

using mesh_test::signedVolume;

// Distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
double pointTriangleDistance(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                             const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  }
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

double clearance(const TriangleMesh& mesh, const Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3i& t : mesh.triangles) {
    best = std::min(best, pointTriangleDistance(p, mesh.vertices[t[0]].cast<double>(),
                                                mesh.vertices[t[1]].cast<double>(),
                                                mesh.vertices[t[2]].cast<double>()));
  }
  return best;
}

TriangleMesh build(const std::string& name) {
  TriangleMesh mesh;
  const Status status = makeProceduralScene(name, &mesh);
  EXPECT_TRUE(status.ok()) << status.message();
  return mesh;
}

void expectBounds(const AlignedBox& box, const Vector3d& lo, const Vector3d& hi, double tol) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(box.min[k], lo[k], tol) << "axis " << k;
    EXPECT_NEAR(box.max[k], hi[k], tol) << "axis " << k;
  }
}

constexpr double kUavRadius = 1.0;

TEST(ProceduralScenes, NamesAreStable) {
  const std::vector<std::string> expected = {"box", "sphere", "room", "plant", "statue", "multistorey"};
  EXPECT_EQ(proceduralSceneNames(), expected);
  for (const std::string& name : expected) EXPECT_TRUE(isProceduralScene(name));
  EXPECT_FALSE(isProceduralScene("Box"));
  EXPECT_FALSE(isProceduralScene(""));
}

TEST(ProceduralScenes, UnknownNameListsKnownOnes) {
  TriangleMesh mesh;
  mesh.vertices.emplace_back(1, 2, 3);
  const Status status = makeProceduralScene("castle", &mesh);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("castle"), std::string::npos);
  for (const std::string& name : proceduralSceneNames()) {
    EXPECT_NE(status.message().find(name), std::string::npos) << status.message();
  }
  EXPECT_FALSE(makeProceduralScene("box", nullptr).ok());
}

TEST(ProceduralScenes, EveryScenePlainAndDeterministic) {
  for (const std::string& name : proceduralSceneNames()) {
    TriangleMesh mesh;
    mesh.vertices.emplace_back(100, 100, 100);
    mesh.triangles.emplace_back(0, 0, 0);
    ASSERT_TRUE(makeProceduralScene(name, &mesh).ok()) << name;
    const TriangleMesh again = build(name);
    EXPECT_EQ(mesh.vertices, again.vertices) << name;
    EXPECT_EQ(mesh.triangles, again.triangles) << name;
    EXPECT_FALSE(mesh.bounds().contains(Vector3d(100, 100, 100))) << name;
    EXPECT_GE(mesh.bounds().min.z(), 0.0) << name;
    const size_t before = mesh.numTriangles();
    mesh.removeDegenerate();
    EXPECT_EQ(mesh.numTriangles(), before) << name;
  }
}

TEST(ProceduralScenes, BoxIsFourMetreCube) {
  const TriangleMesh m = build("box");
  EXPECT_EQ(m.numTriangles(), 12u);
  expectBounds(m.bounds(), Vector3d(-2, -2, 0), Vector3d(2, 2, 4), 0.0);
  EXPECT_NEAR(m.area(), 96.0, 1e-9);
  EXPECT_NEAR(signedVolume(m), 64.0, 1e-9);
}

TEST(ProceduralScenes, SphereHasRadiusTwo) {
  const TriangleMesh m = build("sphere");
  expectBounds(m.bounds(), Vector3d(-2, -2, 0), Vector3d(2, 2, 4), 1e-5);
  for (const Eigen::Vector3f& p : m.vertices) {
    EXPECT_NEAR((p.cast<double>() - Vector3d(0, 0, 2)).norm(), 2.0, 1e-5);
  }
  const double exact = 4.0 / 3.0 * M_PI * 8.0;
  EXPECT_NEAR(signedVolume(m) / exact, 1.0, 0.01);
  EXPECT_LE(m.numTriangles(), 10000u);
}

TEST(ProceduralScenes, RoomFacesInwardWithPillar) {
  const TriangleMesh m = build("room");
  EXPECT_EQ(m.numTriangles(), 24u);
  expectBounds(m.bounds(), Vector3d(-5, -4, 0), Vector3d(5, 4, 4), 0.0);
  // Inward room (-320 m^3) plus the outward 1 x 1 x 4 m pillar.
  EXPECT_NEAR(signedVolume(m), -320.0 + 4.0, 1e-6);
  EXPECT_LT(signedVolume(m), 0.0);
  EXPECT_GT(clearance(m, Vector3d(-2.5, -1.5, 2.0)), kUavRadius);
  EXPECT_LT(clearance(m, Vector3d(2.0, 1.0, 2.0)), 1e-9 + 0.5);
}

TEST(ProceduralScenes, PlantFillsItsBoxExactly) {
  const TriangleMesh m = build("plant");
  const AlignedBox box = m.bounds();
  expectBounds(box, Vector3d(-32.5, -21, 0), Vector3d(32.5, 21, 15), 0.01);
  EXPECT_NEAR(box.size().x(), 65.0, 0.01);
  EXPECT_NEAR(box.size().y(), 42.0, 0.01);
  EXPECT_NEAR(box.size().z(), 15.0, 0.01);
  EXPECT_GT(m.numTriangles(), 1000u);
  EXPECT_LT(m.numTriangles(), 50000u);
  EXPECT_GT(signedVolume(m), 0.0);
}

TEST(ProceduralScenes, PlantFlyableSpacesHaveUavClearance) {
  const TriangleMesh m = build("plant");
  const std::vector<Vector3d> free_points = {
      {7.3, 6.0, 3.5},     // centre of the east hall door
      {-9.5, -3.8, 3.0},   // centre of the south hall door
      {-10.0, 1.0, 5.0},   // inside the hall, under the crane
      {-25.0, -19.2, 2.5}, {-14.0, -19.2, 2.5}, {0.0, -19.2, 2.5},  // narrow passage
      {27.0, -9.0, 7.5},   {27.0, 3.0, 12.5},   // between flues
      {16.5, 0.0, 5.0},    {16.5, 6.0, 9.0},    // under and between gantries
      {-12.0, 6.0, 14.5},  // above the roof
      {-10.0, -14.0, 2.0}, // yard between the hall and the passage
  };
  for (const Vector3d& p : free_points) {
    EXPECT_GT(clearance(m, p), kUavRadius) << p.transpose();
  }
  // The passage is narrow: its walls are within 1.5 m of the centre line.
  EXPECT_LT(clearance(m, Vector3d(-14.0, -19.2, 2.5)), 1.5);
  // A gantry handrail is a thin solid bar where it should be.
  EXPECT_LT(clearance(m, Vector3d(16.5, 12.0 + 0.7, 9.25)), 0.05);
  // All five flues end at 15 m, with their tops 6 m apart along x = 27.
  for (double y : {-12.0, -6.0, 0.0, 6.0, 12.0}) {
    EXPECT_NEAR(clearance(m, Vector3d(27.0, y, 15.2)), 0.2, 1e-4) << y;
  }
}

TEST(ProceduralScenes, StatueWithinItsBoxAndTall) {
  const TriangleMesh m = build("statue");
  const AlignedBox box = m.bounds();
  EXPECT_GE(box.min.x(), -10.0 - 1e-6);
  EXPECT_GE(box.min.y(), -10.0 - 1e-6);
  EXPECT_LE(box.max.x(), 10.0 + 1e-6);
  EXPECT_LE(box.max.y(), 10.0 + 1e-6);
  EXPECT_NEAR(box.min.z(), 0.0, 1e-6);
  EXPECT_LE(box.max.z(), 60.0 + 1e-5);
  EXPECT_GT(box.max.z(), 59.0);
  EXPECT_NEAR(box.size().x(), 20.0, 0.01);
  EXPECT_NEAR(box.size().y(), 20.0, 0.01);
  EXPECT_GT(m.numTriangles(), 1000u);
  EXPECT_LT(m.numTriangles(), 50000u);
  EXPECT_GT(signedVolume(m), 0.0);

  size_t above_55 = 0;
  for (const Eigen::Vector3i& t : m.triangles) {
    if (m.vertices[t[0]].z() > 55.0) ++above_55;
  }
  EXPECT_GT(above_55, 20u);
  // The torch is off the body axis, so there is air between it and the head.
  EXPECT_GT(clearance(m, Vector3d(0.0, 0.0, 57.0)), kUavRadius);
  // The pedestal is stepped: the base is 20 m wide but the die above is narrower.
  EXPECT_GT(clearance(m, Vector3d(9.0, 0.0, 10.0)), kUavRadius);
  EXPECT_LT(clearance(m, Vector3d(9.0, 0.0, 1.0)), 1e-6 + 1.0);
}

TEST(ProceduralScenes, MultistoreyIsLargeWithFlyableDecks) {
  const TriangleMesh m = build("multistorey");
  expectBounds(m.bounds(), Vector3d(-30, -20, 0), Vector3d(30, 20, 45.6), 0.01);
  EXPECT_GT(m.area(), 40000.0);
  EXPECT_GT(signedVolume(m), 0.0);
  // Between two decks (3.3 m apart, 0.3 m slabs) a point half-way up the
  // 3 m gap clears the floor and the ceiling by 1.5 m, away from columns.
  for (const Vector3d& p : {Vector3d(-22.5, 4.25, 1.5), Vector3d(4.5, -12.75, 3.3 * 3 + 1.5),
                            Vector3d(-4.5, -4.25, 3.3 * 7 + 1.5), Vector3d(4.5, 0.0, 3.3 * 11 + 1.5)}) {
    EXPECT_NEAR(clearance(m, p), 1.5, 1e-3) << p.transpose();
  }
  // A parapet gap (3 m wide, mid-bay) lets a UAV in from outside at deck 2.
  EXPECT_GT(clearance(m, Vector3d(-25.0, -20.0, 3.3 * 2 + 1.5)), kUavRadius);
  // Next to the gap the parapet is solid; the slab above stays 0.3 m thick.
  EXPECT_LT(clearance(m, Vector3d(-28.0, -19.9, 3.3 * 2 + 0.5)), 0.15);
  EXPECT_LT(clearance(m, Vector3d(-20.0, 0.0, 3.3 * 2 - 0.15)), 0.2);
  // The stair cores rise above the top deck.
  EXPECT_NEAR(clearance(m, Vector3d(-10.0, -6.0, 46.6)), 1.0, 1e-3);
}

}  // namespace
}  // namespace surface_nbv
