#include "surface_nbv/map/mesh_extractor.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <utility>

#include <gtest/gtest.h>

#include "surface_nbv/sim/mesh_io.h"

namespace surface_nbv {
namespace {

using Eigen::Vector3d;
using Eigen::Vector3i;
using Sdf = std::function<double(const Vector3d&)>;

constexpr double kVoxel = 0.125;  // exact in binary: 32 x 32 x 16 voxels, 4 x 4 x 2 blocks
constexpr double kInf = std::numeric_limits<double>::infinity();

TsdfConfig testConfig(const Vector3d& max = Vector3d(4.0, 4.0, 2.0)) {
  TsdfConfig c;
  c.voxel_size = kVoxel;
  c.bounds = AlignedBox(Vector3d::Zero(), max);
  return c;
}

// phi = sdf clamped to +-3 voxels, w = 1, for the voxels within `band` of the
// surface whose index lies in [lo, hi); their blocks get one new stamp.
void writeSdf(TsdfMap* map, const Sdf& sdf, double band = kInf, Vector3i lo = Vector3i::Zero(),
              Vector3i hi = Vector3i::Constant(1 << 20)) {
  hi = hi.cwiseMin(map->gridVoxels());
  const uint64_t stamp = map->beginChange();
  for (int z = lo.z(); z < hi.z(); ++z) {
    for (int y = lo.y(); y < hi.y(); ++y) {
      for (int x = lo.x(); x < hi.x(); ++x) {
        const Vector3i v(x, y, z);
        const double d = sdf(map->voxelCenter(v));
        if (std::abs(d) > band) continue;
        TsdfVoxel* voxel = map->allocateVoxel(v);
        voxel->phi = static_cast<float>(std::clamp(d, -3 * kVoxel, 3 * kVoxel));
        voxel->w = 1.0f;
        map->mutableBlock(TsdfMap::blockOfVoxel(v))->change_stamp = stamp;
      }
    }
  }
}

Sdf sphere(const Vector3d& c, double r) {
  return [c, r](const Vector3d& p) { return (p - c).norm() - r; };
}

Vector3d normalOf(const TriangleMesh& m, const Eigen::Vector3i& t) {
  const Vector3d a = m.vertices[t[0]].cast<double>();
  return (m.vertices[t[1]].cast<double>() - a).cross(m.vertices[t[2]].cast<double>() - a);
}

Vector3d centroidOf(const TriangleMesh& m, const Eigen::Vector3i& t) {
  return (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]]).cast<double>() / 3.0;
}

// Number of directed edges whose reverse is missing or repeated: 0 for a
// closed, consistently oriented manifold.
int orientedBoundaryEdges(const TriangleMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const Eigen::Vector3i& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  int bad = 0;
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    bad += count != 1 || reverse == directed.end() || reverse->second != 1;
  }
  return bad;
}

TEST(MeshExtractor, HorizontalPlaneIsExactWithKnownArea) {
  TsdfMap map(testConfig());
  writeSdf(&map, [](const Vector3d& p) { return p.z() - 1.03; });
  MeshExtractor extractor;
  EXPECT_EQ(extractor.update(map), 32u);
  const TriangleMesh mesh = extractor.mesh();
  // Cubes span voxel centres 0.0625 .. 3.9375: 31 x 31 cubes, 2 triangles each.
  ASSERT_EQ(mesh.numTriangles(), 2u * 31 * 31);
  EXPECT_EQ(mesh.vertices.size(), 32u * 32);
  EXPECT_EQ(extractor.mesh(false).vertices.size(), 32u * 32 + 2 * 32 * 3 + 3 * 3 * 1);
  for (const Eigen::Vector3f& v : mesh.vertices) ASSERT_NEAR(v.z(), 1.03, 1e-6);
  EXPECT_NEAR(mesh.area(), 3.875 * 3.875, 1e-4);
  for (const Eigen::Vector3i& t : mesh.triangles) ASSERT_GT(normalOf(mesh, t).normalized().z(), 0.999999);
  EXPECT_EQ(extractor.blockMeshes().size(), 16u);  // blocks z = 0 own the cubes of voxel layer 7
}

TEST(MeshExtractor, TiltedPlaneVerticesLieOnItAndNormalsPointToPositivePhi) {
  const Vector3d n = Vector3d(-0.25, 0.0, 1.0).normalized();
  const double d = 0.5 * n.z();  // the plane z = 0.5 + 0.25 x
  TsdfMap map(testConfig());
  writeSdf(&map, [&](const Vector3d& p) { return n.dot(p) - d; });
  MeshExtractor extractor;
  extractor.update(map);
  const TriangleMesh mesh = extractor.mesh();
  ASSERT_EQ(mesh.numTriangles(), 2418u);
  EXPECT_EQ(mesh.vertices.size(), 1280u);
  double worst = 0.0;
  for (const Eigen::Vector3f& v : mesh.vertices) worst = std::max(worst, std::abs(n.dot(v.cast<double>()) - d));
  EXPECT_LT(worst, 1e-4);
  EXPECT_NEAR(mesh.area(), 3.875 * 3.875 * std::sqrt(1.0 + 0.25 * 0.25), 1e-3);
  for (const Eigen::Vector3i& t : mesh.triangles) ASSERT_GT(normalOf(mesh, t).dot(n), 0.0);
}

TEST(MeshExtractor, SphereIsClosedOrientedAndWithinHalfAVoxel) {
  const Vector3d c(2.0, 2.0, 1.0);
  const double r = 0.7;
  TsdfMap map(testConfig());
  writeSdf(&map, sphere(c, r), 4 * kVoxel);
  MeshExtractor extractor;
  extractor.update(map);
  const TriangleMesh mesh = extractor.mesh();
  ASSERT_EQ(mesh.numTriangles(), 1148u);
  EXPECT_EQ(mesh.vertices.size(), 576u);
  double worst = 0.0;
  for (const Eigen::Vector3f& v : mesh.vertices) worst = std::max(worst, std::abs((v.cast<double>() - c).norm() - r));
  EXPECT_LT(worst, 0.5 * kVoxel);
  EXPECT_LT(worst, 0.003);
  EXPECT_NEAR(mesh.area(), 4.0 * M_PI * r * r, 0.02 * 4.0 * M_PI * r * r);
  EXPECT_EQ(orientedBoundaryEdges(mesh), 0);
  double volume = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    ASSERT_GT(normalOf(mesh, t).dot(centroidOf(mesh, t) - c), 0.0);
    volume += mesh.vertices[t[0]].cast<double>().dot(normalOf(mesh, t)) / 6.0;
  }
  EXPECT_NEAR(volume, 4.0 / 3.0 * M_PI * r * r * r, 0.02 * 4.0 / 3.0 * M_PI * r * r * r);
  EXPECT_EQ(static_cast<long>(mesh.vertices.size()) - static_cast<long>(mesh.numTriangles()) / 2, 2);  // V - E + F
}

TEST(MeshExtractor, CavityNormalsPointInwardToTheFreeSpace) {
  const Vector3d c(2.0, 2.0, 1.0);
  TsdfMap map(testConfig());
  writeSdf(&map, [&](const Vector3d& p) { return 0.6 - (p - c).norm(); });
  MeshExtractor extractor;
  extractor.update(map);
  const TriangleMesh mesh = extractor.mesh();
  ASSERT_EQ(mesh.numTriangles(), 908u);
  EXPECT_EQ(orientedBoundaryEdges(mesh), 0);
  for (const Eigen::Vector3i& t : mesh.triangles) ASSERT_LT(normalOf(mesh, t).dot(centroidOf(mesh, t) - c), 0.0);
}

TEST(MeshExtractor, RandomFieldGivesAClosedOrientedSurfaceAcrossBlocks) {
  TsdfMap map(testConfig());
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  const Vector3i g = map.gridVoxels();
  for (int z = 0; z < g.z(); ++z) {
    for (int y = 0; y < g.y(); ++y) {
      for (int x = 0; x < g.x(); ++x) {
        const bool border = x == 0 || y == 0 || z == 0 || x == g.x() - 1 || y == g.y() - 1 || z == g.z() - 1;
        TsdfVoxel* v = map.allocateVoxel(Vector3i(x, y, z));
        v->phi = border ? 1.0f : value(rng);
        v->w = 1.0f;
      }
    }
  }
  MeshExtractor extractor;
  extractor.update(map);
  const TriangleMesh mesh = extractor.mesh();
  ASSERT_EQ(mesh.numTriangles(), 40872u);
  EXPECT_EQ(mesh.vertices.size(), 19544u);
  EXPECT_EQ(orientedBoundaryEdges(mesh), 0);
  EXPECT_GT(orientedBoundaryEdges(extractor.mesh(false)), 0);  // unmerged: open along block faces
}

TEST(MeshExtractor, UnknownCornersProduceNoTriangles) {
  TsdfMap map(testConfig());
  writeSdf(&map, [](const Vector3d& p) { return p.z() - 1.03; });
  MeshExtractor extractor;
  extractor.update(map);
  const size_t full = extractor.mesh().numTriangles();
  // Voxel (10, 10, 7) is just below the plane: its 4 crossing cubes go.
  map.allocateVoxel(Vector3i(10, 10, 7))->w = 0.29f;
  map.mutableBlock(Vector3i(1, 1, 0))->change_stamp = map.beginChange();
  extractor.update(map);
  EXPECT_EQ(extractor.mesh().numTriangles(), full - 8);
  for (const Eigen::Vector3i& t : extractor.mesh().triangles) {
    const Vector3d p = centroidOf(extractor.mesh(), t);
    ASSERT_FALSE(std::abs(p.x() - 1.3125) < kVoxel && std::abs(p.y() - 1.3125) < kVoxel);
  }

  TsdfMap half(testConfig());  // blocks with x index 0 and 1 only
  writeSdf(&half, [](const Vector3d& p) { return p.z() - 1.03; }, kInf, Vector3i::Zero(), Vector3i(16, 32, 16));
  MeshExtractor half_extractor;
  half_extractor.update(half);
  EXPECT_EQ(half_extractor.mesh().numTriangles(), 2u * 15 * 31);
  EXPECT_LT(half_extractor.mesh().bounds().max.x(), 15.5 * kVoxel + 1e-6);
}

// mesh_min_weight >= 0 meshes voxels seen at all (w > it), below W_th too, and
// a voxel never seen (w = 0) still breaks its cubes.
TEST(MeshExtractor, MeshMinWeightMeshesObservedVoxelsBelowTheThreshold) {
  for (float mesh_min : {-1.0f, 0.0f}) {
    TsdfConfig config = testConfig();
    config.mesh_min_weight = mesh_min;
    TsdfMap map(config);
    writeSdf(&map, [](const Vector3d& p) { return p.z() - 1.03; });
    MeshExtractor extractor;
    extractor.update(map);
    const size_t full = extractor.mesh().numTriangles();
    map.allocateVoxel(Vector3i(10, 10, 7))->w = 0.05f;  // seen, below W_th = 0.3
    map.allocateVoxel(Vector3i(20, 20, 7))->w = 0.0f;   // never seen
    map.mutableBlock(Vector3i(1, 1, 0))->change_stamp = map.beginChange();
    map.mutableBlock(Vector3i(2, 2, 0))->change_stamp = map.beginChange();
    extractor.update(map);
    EXPECT_EQ(extractor.mesh().numTriangles(), full - (mesh_min < 0.0f ? 16 : 8)) << mesh_min;
  }
  TsdfConfig bad = testConfig();
  bad.mesh_min_weight = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(bad.validate().message().find("mesh_min_weight"), std::string::npos);
}

TEST(MeshExtractor, IncrementalUpdateRemeshesTheBlockAndItsLowerNeighbours) {
  TsdfMap map(testConfig());
  writeSdf(&map, sphere(Vector3d(2.0, 2.0, 1.0), 0.7));
  MeshExtractor extractor;
  EXPECT_EQ(extractor.update(map), 32u);
  EXPECT_EQ(extractor.update(map), 0u);

  // A bump inside block (2, 2, 1): voxels 16..23 x 16..23 x 8..15.
  writeSdf(&map, sphere(Vector3d(2.5, 2.5, 1.5), 0.3), kInf, Vector3i(16, 16, 8), Vector3i(24, 24, 16));
  ASSERT_EQ(map.blocksChangedSince(map.changeCounter() - 1).size(), 1u);
  EXPECT_EQ(extractor.update(map), 8u);
  const std::vector<Vector3i> expected = {{1, 1, 0}, {2, 1, 0}, {1, 2, 0}, {2, 2, 0},
                                          {1, 1, 1}, {2, 1, 1}, {1, 2, 1}, {2, 2, 1}};
  EXPECT_EQ(extractor.lastUpdatedBlocks(), expected);

  MeshExtractor fresh;
  fresh.update(map);
  ASSERT_EQ(extractor.blockMeshes().size(), fresh.blockMeshes().size());
  for (const auto& [index, bm] : fresh.blockMeshes()) {
    const auto it = extractor.blockMeshes().find(index);
    ASSERT_NE(it, extractor.blockMeshes().end());
    EXPECT_EQ(it->second.mesh.vertices, bm.mesh.vertices);
    EXPECT_EQ(it->second.mesh.triangles, bm.mesh.triangles);
    EXPECT_EQ(it->second.edge_keys, bm.edge_keys);
  }
  EXPECT_EQ(extractor.mesh().vertices, fresh.mesh().vertices);

  // A corner block has no lower neighbour inside the bounds.
  writeSdf(&map, sphere(Vector3d(0.3, 0.3, 0.3), 0.2), kInf, Vector3i::Zero(), Vector3i(8, 8, 8));
  EXPECT_EQ(extractor.update(map), 1u);
  EXPECT_EQ(extractor.lastUpdatedBlocks(), std::vector<Vector3i>{Vector3i::Zero()});
}

TEST(MeshExtractor, FreedAndReplacedBlocksAreFollowed) {
  TsdfMap map(testConfig());
  writeSdf(&map, sphere(Vector3d(2.0, 2.0, 1.0), 0.7));
  MeshExtractor extractor;
  extractor.update(map);
  ASSERT_FALSE(extractor.blockMeshes().empty());

  TsdfMap other(testConfig());  // a plane, only in blocks x = 0 and 1
  writeSdf(&other, [](const Vector3d& p) { return p.z() - 1.03; }, kInf, Vector3i::Zero(), Vector3i(16, 32, 16));
  ASSERT_TRUE(map.adoptBlocks(&other));
  extractor.update(map);
  MeshExtractor fresh;
  fresh.update(map);
  EXPECT_EQ(extractor.mesh().triangles, fresh.mesh().triangles);
  EXPECT_EQ(extractor.mesh().vertices, fresh.mesh().vertices);
  EXPECT_EQ(extractor.mesh().numTriangles(), 2u * 15 * 31);

  map.clear();
  extractor.update(map);
  EXPECT_TRUE(extractor.blockMeshes().empty());
  EXPECT_TRUE(extractor.mesh().empty());
}

TEST(MeshExtractor, ExportsPlyAndStlAndRefusesOtherExtensions) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("snbv_mesh_extractor_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  MeshExtractor extractor;
  EXPECT_FALSE(saveMesh(extractor.mesh(), (dir / "empty.ply").string()).ok());
  TsdfMap map(testConfig());
  writeSdf(&map, sphere(Vector3d(2.0, 2.0, 1.0), 0.7), 4 * kVoxel);
  extractor.update(map);
  const size_t triangles = extractor.mesh().numTriangles();
  for (const std::string name : {"sphere.ply", "sphere.stl"}) {
    const std::string path = (dir / name).string();
    const Status s = saveMesh(extractor.mesh(), path);
    ASSERT_TRUE(s.ok()) << s.message();
    TriangleMesh loaded;
    ASSERT_TRUE(loadMesh(path, MeshLoadOptions(), &loaded).ok());
    EXPECT_EQ(loaded.numTriangles(), triangles) << name;
  }
  const Status bad = saveMesh(extractor.mesh(), (dir / "sphere.obj").string());
  EXPECT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("extension"), std::string::npos) << bad.message();
  EXPECT_FALSE(std::filesystem::exists(dir / "sphere.obj"));
  std::filesystem::remove_all(dir);
}

TEST(MeshExtractor, FullMeshOf100x100x30VoxelsTiming) {
  TsdfMap map(testConfig(Vector3d(12.5, 12.5, 3.75)));
  ASSERT_EQ(map.gridVoxels(), Vector3i(100, 100, 30));
  writeSdf(&map, [](const Vector3d& p) {
    return std::min(p.z() - 1.5 - 0.5 * std::sin(p.x()) * std::cos(p.y()), (p - Vector3d(6, 6, 2)).norm() - 1.2);
  });
  MeshExtractor extractor;
  const auto start = std::chrono::steady_clock::now();
  const size_t blocks = extractor.update(map);
  const auto meshed = std::chrono::steady_clock::now();
  const TriangleMesh mesh = extractor.mesh();
  const auto merged = std::chrono::steady_clock::now();
  const auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  std::cout << "[ timing ] " << blocks << " blocks, " << mesh.numTriangles() << " triangles: update "
            << ms(start, meshed) << " ms, merged mesh() " << ms(meshed, merged) << " ms\n";
  EXPECT_EQ(blocks, 13u * 13 * 4);
  EXPECT_GT(mesh.numTriangles(), 20000u);
}

}  // namespace
}  // namespace surface_nbv
