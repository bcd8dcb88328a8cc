// A model's up axis and its fit into a box (MeshLoadOptions::up_axis,
// fit_size): what a user needs to fly a downloaded model (the paper's statue
// is a Y-up OBJ of free3D.com "20 x 20 x 60 m") without working out its scale.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "surface_nbv/sim/mesh_builder.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/sim/procedural_scenes.h"
#include "surface_nbv/sim/scene_source.h"
#include "surface_nbv/util/cli_args.h"

namespace surface_nbv {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;

void expectBox(const AlignedBox& box, const Vector3d& lo, const Vector3d& hi) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(box.min[k], lo[k], 1e-4) << "min, axis " << k;
    EXPECT_NEAR(box.max[k], hi[k], 1e-4) << "max, axis " << k;
  }
}

TriangleMesh boxMesh(const Vector3d& lo, const Vector3d& hi) {
  MeshBuilder b;
  b.addAlignedBox(lo, hi);
  return b.take();
}

Vector3d areaCentre(const TriangleMesh& mesh) {
  Vector3d sum = Vector3d::Zero();
  double area = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                   c = mesh.vertices[t[2]].cast<double>();
    const double at = 0.5 * (b - a).cross(c - a).norm();
    sum += at * (a + b + c) / 3.0;
    area += at;
  }
  return sum / area;
}

// The text of an OBJ file holding the box lo..hi (8 vertices, 12 triangles).
std::string objBox(const Vector3d& lo, const Vector3d& hi) {
  std::string text = "# box\n";
  for (int k = 0; k < 8; ++k) {
    const Vector3d p((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
    text += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  }
  // Faces of the cube on vertices 1..8 (bit 0: x, bit 1: y, bit 2: z).
  const int faces[6][4] = {{1, 3, 7, 5}, {2, 6, 8, 4}, {1, 5, 6, 2}, {3, 4, 8, 7}, {1, 2, 4, 3}, {5, 7, 8, 6}};
  for (const auto& f : faces) {
    text += "f " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
    text += "f " + std::to_string(f[0]) + " " + std::to_string(f[2]) + " " + std::to_string(f[3]) + "\n";
  }
  return text;
}

// Writes a file `name` in a fresh temporary folder with `write`, loads it as
// a Y-up model fitted to the paper's statue box (20 x 20 x 60 m), and
// removes the folder.
Status loadYUpIntoStatueBox(const std::string& name, TriangleMesh* mesh,
                            const std::function<bool(const std::string&)>& write) {
  std::string pattern = (fs::temp_directory_path() / "nbv_mesh_fit_XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) return Status::Error("no temporary folder");
  const std::string file = (fs::path(pattern) / name).string();
  MeshLoadOptions options;
  options.up_axis = "y";
  options.fit_size = Vector3d(20, 20, 60);
  const Status s = write(file) ? loadMesh(file, options, mesh) : Status::Error("cannot write " + file);
  fs::remove_all(pattern);
  return s;
}

// The scene options of a tool's command line `words` (after the program name).
Status sceneFromWords(std::vector<std::string> words, SceneConfig* config) {
  words.insert(words.begin(), "tool");
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  CliArgs args(sceneOptionNames(), {});
  if (Status s = args.parse(static_cast<int>(argv.size()), argv.data()); !s) return s;
  return sceneConfigFromArgs(args, config);
}

TEST(MeshFit, AYUpModelIsStoodUpright) {
  // Six metres tall along y, as a Y-up export holds it.
  TriangleMesh mesh = boxMesh(Vector3d(0, 0, 0), Vector3d(2, 6, 1));
  MeshLoadOptions options;
  options.up_axis = "y";
  ASSERT_TRUE(options.validate().ok());
  EXPECT_DOUBLE_EQ(applyLoadOptions(options, &mesh), 1.0);
  expectBox(mesh.bounds(), Vector3d(0, -1, 0), Vector3d(2, 0, 6));
}

TEST(MeshFit, TheLargestUniformScaleThatFitsCentredOnTheGround) {
  const TriangleMesh original = boxMesh(Vector3d(1, -2, 5), Vector3d(3, -1, 11));  // 2 x 1 x 6 m
  TriangleMesh mesh = original;
  MeshLoadOptions options;
  options.fit_size = Vector3d(20, 20, 60);
  ASSERT_TRUE(options.validate().ok());
  // x and z bind (20 / 2 = 60 / 6 = 10); y would allow 20.
  EXPECT_NEAR(applyLoadOptions(options, &mesh), 10.0, 1e-12);
  expectBox(mesh.bounds(), Vector3d(-10, -5, 0), Vector3d(10, 5, 60));
  EXPECT_NEAR(mesh.area(), 100.0 * original.area(), 1e-2);

  // The offset moves the fitted model; the crop cuts it after.
  mesh = original;
  options.offset = Vector3d(0, 0, 1);
  options.crop.max.z() = 31.0;
  applyLoadOptions(options, &mesh);
  expectBox(mesh.bounds(), Vector3d(-10, -5, 1), Vector3d(10, 5, 31));

  // Without the fit, the same mesh keeps its place and size.
  mesh = original;
  applyLoadOptions(MeshLoadOptions(), &mesh);
  expectBox(mesh.bounds(), Vector3d(1, -2, 5), Vector3d(3, -1, 11));
}

TEST(MeshFit, AFlatModelFitsByItsOtherAxes) {
  // A ground plate 4 x 2 m with no height: z must not divide by zero.
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 2}, {4, 0, 2}, {4, 2, 2}, {0, 2, 2}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  MeshLoadOptions options;
  options.fit_size = Vector3d(8, 8, 1);
  EXPECT_NEAR(applyLoadOptions(options, &mesh), 2.0, 1e-12);
  expectBox(mesh.bounds(), Vector3d(-4, -2, 0), Vector3d(4, 2, 0));
}

TEST(MeshFit, AYUpObjFileFitsThePapersStatueBox) {
  TriangleMesh mesh;
  const Status s = loadYUpIntoStatueBox("statue.obj", &mesh, [](const std::string& file) {
    std::ofstream out(file);
    out << objBox(Vector3d(-0.25, 0, -0.2), Vector3d(0.25, 3, 0.2));  // 0.5 wide, 3 tall (y), 0.4 deep
    return static_cast<bool>(out);
  });
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(mesh.numTriangles(), 12u);
  // Upright: 3 m tall scaled by 60 / 3 = 20; 0.5 x 0.4 m footprint to 10 x 8 m.
  expectBox(mesh.bounds(), Vector3d(-5, -4, 0), Vector3d(5, 4, 60));
}

// The built-in statue exported Y-up in centimetres, as a downloaded model
// might be, comes back as built (it is 20 x 20 x 60 m, centred, on the
// ground).
TEST(MeshFit, TheStatueSavedYUpInCentimetresComesBackAsBuilt) {
  TriangleMesh statue;
  ASSERT_TRUE(makeProceduralScene("statue", &statue).ok());
  TriangleMesh exported = statue;
  for (Eigen::Vector3f& v : exported.vertices) v = 100.0f * Eigen::Vector3f(v.x(), v.z(), -v.y());
  TriangleMesh loaded;
  const Status s = loadYUpIntoStatueBox("liberty.ply", &loaded,
                                        [&exported](const std::string& file) { return saveMesh(exported, file).ok(); });
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(loaded.numTriangles(), statue.numTriangles());
  expectBox(loaded.bounds(), statue.bounds().min, statue.bounds().max);
  EXPECT_NEAR(loaded.area(), statue.area(), 1e-4 * statue.area());
  // The surface's centre of area, which a shift, a mirror or a wrong turn
  // about x would move (the bounds alone are symmetric).
  EXPECT_LT((areaCentre(loaded) - areaCentre(statue)).norm(), 1e-3);
}

TEST(MeshFit, BadUpAxisOrFitIsRefusedByName) {
  const auto refused = [](const MeshLoadOptions& o, const std::string& word) {
    const Status s = o.validate();
    EXPECT_FALSE(s.ok()) << word;
    EXPECT_NE(s.message().find(word), std::string::npos) << s.message();
  };
  MeshLoadOptions o;
  o.up_axis = "x";
  refused(o, "up_axis");
  o.up_axis = "";
  refused(o, "up_axis");
  o = MeshLoadOptions();
  o.fit_size = Vector3d(20, 0, 60);  // some axes only
  refused(o, "fit_size");
  o.fit_size = Vector3d(20, -20, 60);
  refused(o, "fit_size");
  o.fit_size = Vector3d(20, std::numeric_limits<double>::quiet_NaN(), 60);
  refused(o, "fit_size");
  o.fit_size = Vector3d(20, 20, 60);
  o.scale = 0.5;  // the fit chooses the scale
  refused(o, "scale");
  o.scale = 1.0;
  EXPECT_TRUE(o.validate().ok());
  EXPECT_TRUE(o.fitsToBox());
  EXPECT_FALSE(MeshLoadOptions().fitsToBox());
}

TEST(MeshFit, TheToolsOptionsCarryUpAxisAndFit) {
  SceneConfig config;
  ASSERT_TRUE(sceneFromWords({"--scene", "model.obj", "--up-axis", "y", "--fit-size", "20,20,60"}, &config).ok());
  EXPECT_EQ(config.transform.up_axis, "y");
  EXPECT_EQ(config.transform.fit_size, Vector3d(20, 20, 60));
  // Two sizes, or a fit with a scale, are refused.
  SceneConfig two;
  EXPECT_FALSE(sceneFromWords({"--fit-size", "20,60"}, &two).ok());
  SceneConfig scaled;
  const Status s = sceneFromWords({"--fit-size", "20,20,60", "--scale", "2"}, &scaled);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("scale"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace surface_nbv
