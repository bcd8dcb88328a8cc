#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "eval_test_helpers.h"
#include "surface_nbv/eval/free_space_grid.h"
#include "surface_nbv/eval/visibility_pruner.h"
#include "surface_nbv/sim/mesh_builder.h"
#include "surface_nbv/sim/procedural_scenes.h"

namespace surface_nbv {
namespace {

using Eigen::Vector3d;

TEST(SquaredDistanceToTriangle, MatchesADenseSearch) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Vector3d p(u(rng), u(rng), u(rng));
    double best = 1e9;
    for (int i = 0; i <= 200; ++i) {
      for (int j = 0; i + j <= 200; ++j) {
        best = std::min(best, (p - (a + (b - a) * (i / 200.0) + (c - a) * (j / 200.0))).squaredNorm());
      }
    }
    const double d = squaredDistanceToTriangle(p, a, b, c);
    ASSERT_LE(d, best + 1e-12);
    ASSERT_NEAR(std::sqrt(d), std::sqrt(best), 0.03);
  }
}

// A closed box with 0.3 m walls: outer faces outward, inner faces inward.
TriangleMesh hollowBox(int* outer_triangles) {
  MeshBuilder b;
  b.addAlignedBox(Vector3d(-2, -2, 0), Vector3d(2, 2, 4));
  *outer_triangles = static_cast<int>(b.mesh().numTriangles());
  b.setInward(true);
  b.addAlignedBox(Vector3d(-1.7, -1.7, 0.3), Vector3d(1.7, 1.7, 3.7));
  return b.take();
}

TEST(FreeSpaceGrid, ReachesAroundAClosedBoxButNotInsideIt) {
  int outer = 0;
  const TriangleMesh mesh = hollowBox(&outer);
  FreeSpaceGrid grid;
  ASSERT_TRUE(grid.build(mesh, AlignedBox(Vector3d(-6, -6, 0), Vector3d(6, 6, 8)), 0.5, 1.0, 2));
  EXPECT_EQ(grid.dims(), Eigen::Vector3i(24, 24, 16));
  EXPECT_TRUE(grid.reachable(Vector3d(-4.5, 0.1, 1.0)));
  EXPECT_TRUE(grid.reachable(Vector3d(0.1, 0.1, 5.2)));   // 1.2 m above the roof
  EXPECT_FALSE(grid.reachable(Vector3d(0.1, 0.1, 4.7)));  // within the collision radius
  EXPECT_FALSE(grid.reachable(Vector3d(0.1, 0.1, 2.0)));  // free, but inside the closed box
  EXPECT_FALSE(grid.reachable(Vector3d(0.1, 0.1, 9.0)));  // outside the bounds
  EXPECT_FALSE(grid.reachable(Vector3d(NAN, 0.0, 1.0)));
  // Every free cell is either reachable or inside the box, and blocked cells
  // are exactly those whose centre is within the radius.
  size_t inside = 0, blocked = 0;
  for (int z = 0; z < 16; ++z) {
    for (int y = 0; y < 24; ++y) {
      for (int x = 0; x < 24; ++x) {
        const Vector3d c = Vector3d(-6, -6, 0) + 0.5 * Vector3d(x + 0.5, y + 0.5, z + 0.5);
        double d2 = 1e9;
        for (const Eigen::Vector3i& t : mesh.triangles) {
          d2 = std::min(
              d2, squaredDistanceToTriangle(c, mesh.vertices[t[0]].cast<double>(), mesh.vertices[t[1]].cast<double>(),
                                            mesh.vertices[t[2]].cast<double>()));
        }
        const bool in_box = (c.array().abs().head<2>() < 2.0).all() && c.z() < 4.0;
        blocked += d2 <= 1.0 ? 1 : 0;
        inside += d2 > 1.0 && in_box ? 1 : 0;
        ASSERT_EQ(grid.reachable(c), d2 > 1.0 && !in_box) << c.transpose();
      }
    }
  }
  EXPECT_EQ(grid.numBlocked(), blocked);
  EXPECT_EQ(grid.numReachable(), grid.numCells() - blocked - inside);
  EXPECT_GT(inside, 0u);
}

TEST(FreeSpaceGrid, ClearanceNeverOverstatesTheDistanceToReachableSpace) {
  int outer = 0;
  const TriangleMesh mesh = hollowBox(&outer);
  FreeSpaceGrid grid;
  const Vector3d lo(-6, -6, 0);
  ASSERT_TRUE(grid.build(mesh, AlignedBox(lo, Vector3d(6, 6, 8)), 0.5, 1.0));
  std::vector<AlignedBox> reachable_cells;
  for (int z = 0; z < 16; ++z) {
    for (int y = 0; y < 24; ++y) {
      for (int x = 0; x < 24; ++x) {
        const Vector3d c0 = lo + 0.5 * Vector3d(x, y, z);
        if (grid.reachable(c0 + Vector3d::Constant(0.25)))
          reachable_cells.emplace_back(c0, c0 + Vector3d::Constant(0.5));
      }
    }
  }
  double largest = 0.0;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vector3d p = lo + Vector3d(12 * u(rng), 12 * u(rng), 8 * u(rng));
    double nearest = 1e9;
    for (const AlignedBox& b : reachable_cells)
      nearest = std::min(nearest, (p - p.cwiseMax(b.min).cwiseMin(b.max)).norm());
    const double clearance = std::max(0, grid.cellsToReachable(p) - 1) * 0.5;
    ASSERT_LE(clearance, nearest + 1e-9) << p.transpose();
    ASSERT_GE(clearance, nearest - 2.0 * std::sqrt(3.0) * 0.5) << p.transpose();
    largest = std::max(largest, clearance);
  }
  EXPECT_GE(largest, 1.0);  // the box's inside is far from reachable space
  EXPECT_EQ(grid.cellsToReachable(Vector3d(0, 0, 100)), -1);
  EXPECT_EQ(grid.cellsToReachable(Vector3d(-4.5, 0.1, 1.0)), 0);
}

TEST(FreeSpaceGrid, RefusesBadBoundsAndHugeGrids) {
  FreeSpaceGrid grid;
  const TriangleMesh mesh = MeshBuilder().mesh();
  EXPECT_FALSE(grid.build(mesh, AlignedBox(), 0.5, 1.0));
  EXPECT_FALSE(grid.build(mesh, AlignedBox(Vector3d::Zero(), Vector3d::Ones()), 0.0, 1.0));
  const Status s = grid.build(mesh, AlignedBox(Vector3d::Zero(), Vector3d::Constant(1000)), 0.1, 1.0);
  EXPECT_FALSE(s);
  EXPECT_NE(s.message().find("free_space_cell"), std::string::npos) << s.message();
}

struct Pruned {
  SurfaceCloud cloud;
  std::vector<uint8_t> visible;
  size_t count = 0;
};

Pruned prune(const TriangleMesh& mesh, const EvalConfig& config) {
  Pruned out;
  EXPECT_TRUE(SurfaceSampler(config.spacing(), config.seed).sample(mesh, 1000000, &out.cloud));
  FreeSpaceGrid grid;
  EXPECT_TRUE(grid.build(mesh, config.sensorBounds(mesh.bounds()), config.free_space_cell, config.collision_radius));
  std::unique_ptr<RaycastScene> scene;
  EXPECT_TRUE(RaycastScene::create(mesh, &scene));
  out.count = VisibilityPruner(*scene, grid, config).prune(&out.cloud, &out.visible);
  return out;
}

TEST(VisibilityPruner, PrunesTheInsideOfAClosedBoxAndItsFloor) {
  int outer = 0;
  const TriangleMesh mesh = hollowBox(&outer);
  EvalConfig config;
  config.point_spacing = 0.1;
  config.threads = 2;
  const Pruned p = prune(mesh, config);
  size_t expected = 0, outer_faces = 0;
  for (size_t i = 0; i < p.cloud.size(); ++i) {
    const int t = p.cloud.triangles[i];
    const bool bottom = t < outer && p.cloud.normals[i].z() < -0.5f;
    const bool visible = t < outer && !bottom;
    expected += visible ? 1 : 0;
    outer_faces += t < outer ? 1 : 0;
    ASSERT_EQ(p.visible[i] != 0, visible) << "sample " << i << " at " << p.cloud.points[i].transpose();
  }
  EXPECT_EQ(p.count, expected);
  EXPECT_NEAR(static_cast<double>(expected) / outer_faces, 5.0 / 6.0, 0.01);
  std::printf("hollow box: %zu samples, %zu visible (outer faces but the floor), %zu pruned\n", p.cloud.size(), p.count,
              p.cloud.size() - p.count);
}

TEST(VisibilityPruner, SeesASingleSheetRoomFromOutsideAndTurnsItsNormalsOut) {
  TriangleMesh room;
  ASSERT_TRUE(makeProceduralScene("room", &room));  // walls wound inward, a pillar inside
  EvalConfig config;
  config.point_spacing = 0.2;
  const Pruned p = prune(room, config);
  size_t shell_samples = 0;
  for (size_t i = 0; i < p.cloud.size(); ++i) {
    const Eigen::Vector3f q = p.cloud.points[i], n = p.cloud.normals[i];
    // Walls and ceiling (the pillar's top lies in the ceiling's plane); not the floor.
    const bool floor = q.z() < 1e-3f && std::abs(n.z()) > 0.5f;
    const bool shell = !floor && (std::abs(q.x()) > 4.999f || std::abs(q.y()) > 3.999f || q.z() > 3.999f);
    shell_samples += shell ? 1 : 0;
    ASSERT_EQ(p.visible[i] != 0, shell) << q.transpose();
    if (!shell) continue;
    // Seen from outside: the normal now points away from the room.
    const Eigen::Vector3f out = (q - Eigen::Vector3f(0, 0, 2)).cwiseQuotient(Eigen::Vector3f(5, 4, 2));
    ASSERT_GT(n.dot(out), 0.0f) << q.transpose();
  }
  EXPECT_EQ(p.count, shell_samples);
}

TEST(VisibilityPruner, APlainBoxShowsAllButItsFloorAndNothingWithoutFreeSpace) {
  const TriangleMesh box = eval_test::gridBox(eval_test::boxLo(), eval_test::boxHi(), 4.0);
  EvalConfig config;
  config.point_spacing = 0.2;
  const Pruned p = prune(box, config);
  size_t not_floor = 0;
  for (size_t i = 0; i < p.cloud.size(); ++i) {
    const bool floor = p.cloud.normals[i].z() < -0.5f;
    not_floor += floor ? 0 : 1;
    ASSERT_EQ(p.visible[i] != 0, !floor) << p.cloud.points[i].transpose();
  }
  EXPECT_EQ(p.count, not_floor);
  config.collision_radius = 6.0;  // every cell of the bounds is too close to the box
  EXPECT_EQ(prune(box, config).count, 0u);
}

}  // namespace
}  // namespace surface_nbv
