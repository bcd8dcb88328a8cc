#include "surface_nbv/sim/mesh_io.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "surface_nbv/sim/mesh_builder.h"

namespace surface_nbv {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;

constexpr double kInf = std::numeric_limits<double>::infinity();

// A COLLADA 1.4.1 document with one triangle (0,0,0), (1,0,0), (0,0,3) in a
// node translated by `translate`, with the given <asset> unit and up axis.
std::string colladaTriangle(const std::string& unit_meter, const std::string& up_axis,
                            const std::string& translate = "0 0 0") {
  return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>
    <unit name="unit" meter=")" +
         unit_meter + R"("/>
    <up_axis>)" +
         up_axis + R"(</up_axis>
  </asset>
  <library_geometries>
    <geometry id="tri" name="tri">
      <mesh>
        <source id="tri-pos">
          <float_array id="tri-pos-array" count="9">0 0 0 1 0 0 0 0 3</float_array>
          <technique_common>
            <accessor source="#tri-pos-array" count="3" stride="3">
              <param name="X" type="float"/>
              <param name="Y" type="float"/>
              <param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="tri-vtx">
          <input semantic="POSITION" source="#tri-pos"/>
        </vertices>
        <triangles count="1">
          <input semantic="VERTEX" source="#tri-vtx" offset="0"/>
          <p>0 1 2</p>
        </triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene" name="scene">
      <node id="node" name="node">
        <translate>)" +
         translate + R"(</translate>
        <instance_geometry url="#tri"/>
      </node>
    </visual_scene>
  </library_visual_scenes>
  <scene>
    <instance_visual_scene url="#scene"/>
  </scene>
</COLLADA>
)";
}

void expectBounds(const AlignedBox& box, const Vector3d& lo, const Vector3d& hi, double tol) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(box.min[k], lo[k], tol) << "min, axis " << k;
    EXPECT_NEAR(box.max[k], hi[k], tol) << "max, axis " << k;
  }
}

// A mesh with recognisable content, to check that failing calls leave it alone.
TriangleMesh sentinelMesh() {
  MeshBuilder b;
  b.addBox(Vector3d(7, 8, 9), Vector3d(1, 2, 3));
  return b.take();
}

void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]) << i;
  for (size_t i = 0; i < a.triangles.size(); ++i) EXPECT_EQ(a.triangles[i], b.triangles[i]) << i;
}

// Area of the triangles whose three vertices satisfy `pred`.
template <typename Pred>
double areaWhere(const TriangleMesh& mesh, Pred pred) {
  TriangleMesh sub;
  sub.vertices = mesh.vertices;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    if (pred(mesh.vertices[t[0]]) && pred(mesh.vertices[t[1]]) && pred(mesh.vertices[t[2]])) sub.triangles.push_back(t);
  }
  return sub.area();
}

class MeshIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = (fs::temp_directory_path() / "nbv_mesh_io_XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string writeFile(const std::string& name, const std::string& content) const {
    const std::string p = path(name);
    std::ofstream out(p, std::ios::binary);
    out << content;
    return p;
  }

  fs::path dir_;
};

// ---- (a) COLLADA up axis and unit ----

TEST_F(MeshIoTest, ZUpColladaStaysZUp) {
  const std::string file = writeFile("tri_z_up.dae", colladaTriangle("1", "Z_UP"));
  TriangleMesh mesh;
  const Status s = loadMesh(file, MeshLoadOptions(), &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(mesh.numTriangles(), 1u);
  // Assimp's default conversion to Y-up would put the 3 m extent on y.
  expectBounds(mesh.bounds(), Vector3d(0, 0, 0), Vector3d(1, 0, 3), 1e-6);
  EXPECT_NEAR(mesh.area(), 1.5, 1e-6);
}

TEST_F(MeshIoTest, YUpColladaIsNotRotatedEither) {
  const std::string file = writeFile("tri_y_up.dae", colladaTriangle("1", "Y_UP"));
  TriangleMesh mesh;
  const Status s = loadMesh(file, MeshLoadOptions(), &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  expectBounds(mesh.bounds(), Vector3d(0, 0, 0), Vector3d(1, 0, 3), 1e-6);
}

TEST_F(MeshIoTest, ColladaUnitScaleIsApplied) {
  const std::string file = writeFile("tri_inch.dae", colladaTriangle("0.0254", "Z_UP"));
  TriangleMesh mesh;
  const Status s = loadMesh(file, MeshLoadOptions(), &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  expectBounds(mesh.bounds(), Vector3d(0, 0, 0), Vector3d(0.0254, 0, 3 * 0.0254), 1e-7);
  EXPECT_NEAR(mesh.area(), 1.5 * 0.0254 * 0.0254, 1e-9);
}

TEST_F(MeshIoTest, ColladaNodeTransformUnitScaleAndOptionsCompose) {
  // Node translation (10, 0, 2) in file units, then the inch unit, then
  // p' = 2 p + (1, -1, 0.5).
  const std::string file = writeFile("tri_node.dae", colladaTriangle("0.0254", "Z_UP", "10 0 2"));
  MeshLoadOptions options;
  options.scale = 2.0;
  options.offset = Vector3d(1, -1, 0.5);
  TriangleMesh mesh;
  const Status s = loadMesh(file, options, &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  const double u = 0.0254;
  expectBounds(mesh.bounds(), Vector3d(2 * 10 * u + 1, -1, 2 * 2 * u + 0.5),
               Vector3d(2 * 11 * u + 1, -1, 2 * 5 * u + 0.5), 1e-6);
}

// ---- (b) scale and offset ----

TEST(MeshIo, ApplyLoadOptionsScalesAndOffsetsEveryVertex) {
  MeshBuilder b;
  b.addAlignedBox(Vector3d(-1, 0, 2), Vector3d(3, 1, 4));
  const TriangleMesh original = b.take();
  TriangleMesh mesh = original;
  MeshLoadOptions options;
  options.scale = 2.5;
  options.offset = Vector3d(10, -20, 0.5);
  applyLoadOptions(options, &mesh);
  ASSERT_EQ(mesh.vertices.size(), original.vertices.size());
  ASSERT_EQ(mesh.triangles, original.triangles);
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vector3d expected = 2.5 * original.vertices[i].cast<double>() + options.offset;
    EXPECT_NEAR((mesh.vertices[i].cast<double>() - expected).norm(), 0.0, 1e-5) << i;
  }
  expectBounds(mesh.bounds(), Vector3d(7.5, -20, 5.5), Vector3d(17.5, -17.5, 10.5), 1e-5);
  // Box 4 x 1 x 2: area 2 (4 + 8 + 2) = 28, scaled by s^2.
  EXPECT_NEAR(original.area(), 28.0, 1e-9);
  EXPECT_NEAR(mesh.area(), 28.0 * 2.5 * 2.5, 1e-3);
}

TEST_F(MeshIoTest, LoadMeshAppliesScaleAndOffset) {
  MeshBuilder b;
  b.addAlignedBox(Vector3d(0, 0, 0), Vector3d(2, 3, 4));
  const std::string file = path("box.ply");
  ASSERT_TRUE(saveMesh(b.mesh(), file).ok());
  MeshLoadOptions options;
  options.scale = 0.5;
  options.offset = Vector3d(-1, 2, 3);
  TriangleMesh mesh;
  const Status s = loadMesh(file, options, &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  expectBounds(mesh.bounds(), Vector3d(-1, 2, 3), Vector3d(0, 3.5, 5), 1e-6);
  EXPECT_NEAR(mesh.area(), 0.25 * 2 * (6 + 8 + 12), 1e-5);
}

TEST(MeshIo, LoadOptionsValidate) {
  MeshLoadOptions ok;
  EXPECT_TRUE(ok.validate().ok());
  EXPECT_FALSE(ok.hasCrop());

  MeshLoadOptions o;
  o.scale = 0.0;
  EXPECT_FALSE(o.validate().ok());
  o.scale = -1.0;
  EXPECT_FALSE(o.validate().ok());
  o.scale = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(o.validate().ok());

  o = MeshLoadOptions();
  o.offset.y() = kInf;
  EXPECT_FALSE(o.validate().ok());

  o = MeshLoadOptions();
  o.crop.min.z() = 5.0;
  o.crop.max.z() = 4.0;
  EXPECT_FALSE(o.validate().ok());

  o = MeshLoadOptions();
  o.crop.max.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(o.validate().ok());

  o = MeshLoadOptions();
  o.crop.max.z() = 15.0;
  EXPECT_TRUE(o.validate().ok());
  EXPECT_TRUE(o.hasCrop());
}

TEST_F(MeshIoTest, InvalidOptionsFailNamingTheFileAndLeaveMeshUnchanged) {
  MeshBuilder b;
  b.addAlignedBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  const std::string file = path("unit.stl");
  ASSERT_TRUE(saveMesh(b.mesh(), file).ok());
  MeshLoadOptions options;
  options.scale = -2.0;
  TriangleMesh mesh = sentinelMesh();
  const Status s = loadMesh(file, options, &mesh);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find(file), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("scale"), std::string::npos) << s.message();
  expectSameMesh(mesh, sentinelMesh());
}

// ---- (c) crop ----

TEST(MeshIo, CropCubeCutsWallsAtPlaneAndDropsRoof) {
  MeshBuilder b;
  b.addAlignedBox(Vector3d(-2, -2, 0), Vector3d(2, 2, 4));
  const TriangleMesh cube = b.take();
  ASSERT_NEAR(cube.area(), 96.0, 1e-9);

  const AlignedBox box(Vector3d::Constant(-kInf), Vector3d(kInf, kInf, 3.0));
  const TriangleMesh cropped = cropMesh(cube, box);
  expectBounds(cropped.bounds(), Vector3d(-2, -2, 0), Vector3d(2, 2, 3), 0.0);
  // Floor 4 x 4 plus four walls 4 x 3.
  EXPECT_NEAR(cropped.area(), 16.0 + 4 * 4 * 3, 1e-9);
  EXPECT_NEAR(areaWhere(cropped, [](const Eigen::Vector3f& p) { return p.z() == 0.0f; }), 16.0, 1e-9);
  // Nothing lies in the cut plane: the roof is gone, not moved down.
  EXPECT_EQ(areaWhere(cropped, [](const Eigen::Vector3f& p) { return p.z() == 3.0f; }), 0.0);
  for (const Eigen::Vector3i& t : cropped.triangles) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(t[k], 0);
      ASSERT_LT(t[k], static_cast<int>(cropped.vertices.size()));
    }
  }
  // Each wall keeps exactly 12 m^2.
  for (int axis = 0; axis < 2; ++axis) {
    for (float side : {-2.0f, 2.0f}) {
      EXPECT_NEAR(areaWhere(cropped, [&](const Eigen::Vector3f& p) { return p[axis] == side; }), 12.0, 1e-9)
          << "axis " << axis << " side " << side;
    }
  }
  // Unused vertices are dropped: every vertex is referenced.
  std::vector<bool> used(cropped.vertices.size(), false);
  for (const Eigen::Vector3i& t : cropped.triangles) {
    for (int k = 0; k < 3; ++k) used[t[k]] = true;
  }
  for (size_t i = 0; i < used.size(); ++i) EXPECT_TRUE(used[i]) << i;
}

TEST(MeshIo, CropKeepsFaceLyingOnTheBoxBoundary) {
  MeshBuilder b;
  b.addAlignedBox(Vector3d(-2, -2, 0), Vector3d(2, 2, 4));
  const AlignedBox box(Vector3d::Constant(-kInf), Vector3d(kInf, kInf, 4.0));
  EXPECT_NEAR(cropMesh(b.mesh(), box).area(), 96.0, 1e-9);
}

TEST(MeshIo, CropCutsStraddlingTriangleInsteadOfDroppingIt) {
  TriangleMesh tri;
  tri.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 0, 2}};
  tri.triangles = {{0, 1, 2}};
  ASSERT_NEAR(tri.area(), 2.0, 1e-12);
  const AlignedBox below(Vector3d::Constant(-kInf), Vector3d(kInf, kInf, 1.0));
  const TriangleMesh cut = cropMesh(tri, below);
  ASSERT_FALSE(cut.empty());
  // A trapezoid: the triangle minus its top corner triangle of legs 1 and 1.
  EXPECT_NEAR(cut.area(), 1.5, 1e-9);
  expectBounds(cut.bounds(), Vector3d(0, 0, 0), Vector3d(2, 0, 1), 0.0);

  const AlignedBox above(Vector3d(-kInf, -kInf, 1.0), Vector3d::Constant(kInf));
  const TriangleMesh top = cropMesh(tri, above);
  EXPECT_NEAR(top.area(), 0.5, 1e-9);
  expectBounds(top.bounds(), Vector3d(0, 0, 1), Vector3d(1, 0, 2), 0.0);
}

TEST(MeshIo, CropAgainstAllSixPlanes) {
  // A large triangle in the plane z = 0.5 covering the square [-1, 1]^2.
  TriangleMesh tri;
  tri.vertices = {{-10, -10, 0.5f}, {30, -10, 0.5f}, {-10, 30, 0.5f}};
  tri.triangles = {{0, 1, 2}};
  const AlignedBox box(Vector3d(-1, -1, 0), Vector3d(1, 1, 1));
  const TriangleMesh cut = cropMesh(tri, box);
  EXPECT_NEAR(cut.area(), 4.0, 1e-9);
  expectBounds(cut.bounds(), Vector3d(-1, -1, 0.5), Vector3d(1, 1, 0.5), 0.0);

  // The same triangle entirely above the box is dropped.
  const AlignedBox low(Vector3d(-1, -1, 0), Vector3d(1, 1, 0.25));
  EXPECT_TRUE(cropMesh(tri, low).empty());
}

TEST(MeshIo, CropWithInfiniteBoxKeepsEverything) {
  MeshBuilder b;
  b.addSphere(Vector3d(1, 2, 3), 1.5, 8, 16);
  const TriangleMesh sphere = b.take();
  const TriangleMesh cropped = cropMesh(sphere, MeshLoadOptions().crop);
  EXPECT_EQ(cropped.numTriangles(), sphere.numTriangles());
  EXPECT_EQ(cropped.vertices.size(), sphere.vertices.size());
  EXPECT_DOUBLE_EQ(cropped.area(), sphere.area());
}

TEST_F(MeshIoTest, LoadMeshAppliesCropAfterScaleAndOffset) {
  MeshBuilder b;
  b.addAlignedBox(Vector3d(-1, -1, 0), Vector3d(1, 1, 2));
  const std::string file = path("cube.ply");
  ASSERT_TRUE(saveMesh(b.mesh(), file).ok());
  // Scaled to the 4 m cube [-2, 2]^2 x [0, 4], then cropped at z = 3.
  MeshLoadOptions options;
  options.scale = 2.0;
  options.crop.max.z() = 3.0;
  TriangleMesh mesh;
  const Status s = loadMesh(file, options, &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  expectBounds(mesh.bounds(), Vector3d(-2, -2, 0), Vector3d(2, 2, 3), 1e-6);
  EXPECT_NEAR(mesh.area(), 64.0, 1e-5);
}

// ---- (d) save / load round trip ----

class MeshIoRoundTrip : public MeshIoTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(MeshIoRoundTrip, SameAreaBoundsAndTriangleCount) {
  MeshBuilder b;
  b.addBox(Vector3d(1, -2, 3), Vector3d(2, 3, 4), 0.3);
  b.addCylinder(Vector3d(5, 5, 0), Vector3d(5, 5, 6), 0.75, 24);
  b.addSphere(Vector3d(-4, 0, 2), 1.25, 10, 20);
  const TriangleMesh original = b.take();
  const std::string file = path("round_trip." + GetParam());
  const Status saved = saveMesh(original, file);
  ASSERT_TRUE(saved.ok()) << saved.message();
  EXPECT_TRUE(fs::exists(file));
  EXPECT_FALSE(fs::exists(file + ".tmp"));

  TriangleMesh loaded;
  const Status s = loadMesh(file, MeshLoadOptions(), &loaded);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(loaded.numTriangles(), original.numTriangles());
  EXPECT_NEAR(loaded.area(), original.area(), 1e-6 * original.area());
  const AlignedBox a = original.bounds(), c = loaded.bounds();
  expectBounds(c, a.min, a.max, 1e-6);
}

TEST_P(MeshIoRoundTrip, OverwritesAnExistingFile) {
  const std::string file = writeFile("existing." + GetParam(), "old content");
  MeshBuilder b;
  b.addAlignedBox(Vector3d(0, 0, 0), Vector3d(1, 2, 3));
  ASSERT_TRUE(saveMesh(b.mesh(), file).ok());
  TriangleMesh loaded;
  const Status s = loadMesh(file, MeshLoadOptions(), &loaded);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_NEAR(loaded.area(), 22.0, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshIoRoundTrip, ::testing::Values("ply", "stl", "PLY"));

// ---- (e) invalid files ----

void expectLoadFails(const std::string& file, const std::string& must_contain) {
  TriangleMesh mesh = sentinelMesh();
  const Status s = loadMesh(file, MeshLoadOptions(), &mesh);
  EXPECT_FALSE(s.ok()) << file;
  EXPECT_FALSE(s.message().empty());
  EXPECT_NE(s.message().find(must_contain), std::string::npos) << "message: " << s.message();
  expectSameMesh(mesh, sentinelMesh());
}

TEST_F(MeshIoTest, MissingFileFails) { expectLoadFails(path("does_not_exist.dae"), path("does_not_exist.dae")); }

TEST_F(MeshIoTest, DirectoryFails) { expectLoadFails(dir_.string(), dir_.string()); }

TEST(MeshIo, EmptyPathFails) { expectLoadFails("", "empty"); }

TEST_F(MeshIoTest, GarbageFileFails) {
  std::string bytes;
  uint32_t x = 12345u;
  for (int i = 0; i < 4096; ++i) {
    x = x * 1664525u + 1013904223u;
    bytes.push_back(static_cast<char>(x >> 24));
  }
  for (const std::string name : {"garbage.dae", "garbage.stl", "garbage.ply", "garbage.bin"}) {
    const std::string file = writeFile(name, bytes);
    expectLoadFails(file, file);
  }
}

TEST_F(MeshIoTest, TruncatedColladaFails) {
  const std::string full = colladaTriangle("1", "Z_UP");
  const std::string file = writeFile("truncated.dae", full.substr(0, full.size() / 2));
  expectLoadFails(file, file);
}

TEST_F(MeshIoTest, EmptyFileFails) {
  for (const std::string name : {"empty.dae", "empty.stl", "empty.ply"}) {
    const std::string file = writeFile(name, "");
    ASSERT_EQ(fs::file_size(file), 0u);
    expectLoadFails(file, file);
  }
}

TEST_F(MeshIoTest, CropLeavingNothingFails) {
  const std::string file = writeFile("tri.dae", colladaTriangle("1", "Z_UP"));
  MeshLoadOptions options;
  options.crop.min.z() = 10.0;
  TriangleMesh mesh = sentinelMesh();
  const Status s = loadMesh(file, options, &mesh);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find(file), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("crop"), std::string::npos) << s.message();
  expectSameMesh(mesh, sentinelMesh());
}

// ---- (f) save errors ----

TEST_F(MeshIoTest, SaveRejectsUnsupportedExtension) {
  MeshBuilder b;
  b.addAlignedBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  for (const std::string name : {"mesh.obj", "mesh.dae", "mesh", "mesh.ply.txt"}) {
    const std::string file = path(name);
    const Status s = saveMesh(b.mesh(), file);
    EXPECT_FALSE(s.ok()) << name;
    EXPECT_NE(s.message().find(file), std::string::npos) << s.message();
    EXPECT_NE(s.message().find(".ply"), std::string::npos) << s.message();
    EXPECT_FALSE(fs::exists(file)) << name;
  }
}

TEST_F(MeshIoTest, SaveRejectsEmptyMesh) {
  const std::string file = path("empty.ply");
  const Status s = saveMesh(TriangleMesh(), file);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find(file), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("empty"), std::string::npos) << s.message();
  EXPECT_FALSE(fs::exists(file));
}

TEST_F(MeshIoTest, SaveIntoMissingDirectoryFails) {
  MeshBuilder b;
  b.addAlignedBox(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  const std::string file = path("no_such_dir/mesh.stl");
  const Status s = saveMesh(b.mesh(), file);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find(file), std::string::npos) << s.message();
}

// ---- (g) the power plant scene, when the shared scenes are present ----

#ifdef NBV_SOURCE_DIR
std::string powerplantPath() { return std::string(NBV_SOURCE_DIR) + "/../shared/scenes/powerplant.dae"; }

TEST(MeshIoPowerplant, LoadsZUpInMetres) {
  const std::string file = powerplantPath();
  if (!fs::exists(file)) GTEST_SKIP() << file << " not found";
  TriangleMesh mesh;
  const Status s = loadMesh(file, MeshLoadOptions(), &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_NEAR(static_cast<double>(mesh.numTriangles()), 4700.0, 100.0);
  expectBounds(mesh.bounds(), Vector3d(-52.5, -29.1, 0.0), Vector3d(46.6, 35.5, 48.0), 0.1);
}

TEST(MeshIoPowerplant, ScaledAndCroppedFitsThePlantBox) {
  const std::string file = powerplantPath();
  if (!fs::exists(file)) GTEST_SKIP() << file << " not found";
  MeshLoadOptions options;
  options.scale = 0.656;
  options.crop.max.z() = 15.0;
  TriangleMesh mesh;
  const Status s = loadMesh(file, options, &mesh);
  ASSERT_TRUE(s.ok()) << s.message();
  const AlignedBox box = mesh.bounds();
  EXPECT_NEAR(box.size().x(), 65.0, 0.5);
  EXPECT_NEAR(box.size().y(), 42.0, 0.5);
  EXPECT_NEAR(box.min.z(), 0.0, 1e-3);
  EXPECT_NEAR(box.max.z(), 15.0, 1e-6);
  // The scale is applied before the crop: x and y are the unscaled ones times 0.656.
  EXPECT_NEAR(box.min.x(), -52.52 * 0.656, 0.1);
  EXPECT_NEAR(box.max.y(), 35.50 * 0.656, 0.1);
}
#endif

}  // namespace
}  // namespace surface_nbv
