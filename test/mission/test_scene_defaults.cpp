// What a mission derives from its scene when no config gives it
// (scene_defaults.h): the size classes, the bounds, the take-off pose, the
// given keys that win, the refusals; and whole missions with no config on
// procedural scenes written to .obj / .ply / .stl files and loaded back, far
// from the origin, below z = 0 and in millimetres.
#include "surface_nbv/mission/scene_defaults.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "surface_nbv/eval/evaluator.h"
#include "surface_nbv/map/mesh_extractor.h"
#include "surface_nbv/mission/mission_runner.h"
#include "surface_nbv/sim/mesh_builder.h"
#include "surface_nbv/sim/procedural_scenes.h"
#include "surface_nbv/sim/raycast_scene.h"
#include "surface_nbv/util/cli_args.h"

using namespace surface_nbv;

namespace {

std::string tempPath(const std::string& name) { return ::testing::TempDir() + "/scene_defaults_" + name; }

// assimp reads OBJ; mesh_io writes only PLY and STL.
void writeObj(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path);
  out.precision(9);
  for (const Eigen::Vector3f& v : mesh.vertices) out << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const Eigen::Vector3i& t : mesh.triangles) out << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
}

TriangleMesh procedural(const std::string& name) {
  TriangleMesh mesh;
  EXPECT_TRUE(makeProceduralScene(name, &mesh).ok()) << name;
  return mesh;
}

TriangleMesh alignedBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  MeshBuilder b;
  b.addAlignedBox(lo, hi);
  return b.mesh();
}

const std::string kPackage = NBV_SOURCE_DIR;

// Derives into *c, after a config file of `yaml` when one is given.
Status derive(const TriangleMesh& mesh, MissionConfig* c, SceneDefaults* d, const std::string& yaml = "",
              SceneDefaultsOptions options = SceneDefaultsOptions()) {
  if (!yaml.empty()) {
    const std::string file = tempPath("given.yaml");
    std::ofstream(file) << yaml;
    if (Status s = loadMissionConfig(file, c); !s) return s;
    options.config_file = true;
  }
  return deriveSceneDefaults(mesh, kPackage, c, d, options);
}

std::string value(const SceneDefaults& d, const std::string& key) {
  for (const DerivedKey& k : d.derived)
    if (k.key == key) return k.value;
  return "";
}

bool derived(const SceneDefaults& d, const std::string& key) { return !value(d, key).empty(); }

TEST(SceneDefaults, DistanceToMeshIsThePointTriangleDistance) {
  TriangleMesh tri;
  tri.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.triangles = {{0, 1, 2}};
  EXPECT_NEAR(distanceToMesh(tri, {0.2, 0.2, 3.0}), 3.0, 1e-6);        // above the face
  EXPECT_NEAR(distanceToMesh(tri, {-1.0, 0.5, 0.0}), 1.0, 1e-6);       // beside an edge
  EXPECT_NEAR(distanceToMesh(tri, {2.0, 0.0, 0.0}), 1.0, 1e-6);        // beyond a vertex
  EXPECT_NEAR(distanceToMesh(tri, {1.0, 1.0, 0.0}), std::sqrt(0.5), 1e-6);  // off the hypotenuse
  EXPECT_TRUE(std::isinf(distanceToMesh(TriangleMesh(), {0, 0, 0})));
}

// The 4 m box: the small class (config/box.yaml's camera and voxels), the
// bounds its box plus the 8 m range with the floor at the ground, the
// take-off beside its -x face facing it, its ball clear of the mesh.
TEST(SceneDefaults, ASmallSceneGetsTheBoxConfigsCameraBoundsAndAStartFacingIt) {
  const TriangleMesh box = procedural("box");
  MissionConfig c;
  SceneDefaults d;
  ASSERT_TRUE(derive(box, &c, &d).ok());
  EXPECT_EQ(d.size_class, "small");
  EXPECT_DOUBLE_EQ(c.tsdf.voxel_size, 0.1);
  EXPECT_DOUBLE_EQ(c.camera.min_range, 0.5);
  EXPECT_DOUBLE_EQ(c.camera.max_range, 8.0);
  EXPECT_DOUBLE_EQ(c.surface.camera.max_range, 8.0);  // the planner's camera is the renderer's
  EXPECT_DOUBLE_EQ(c.explorer.gaze.camera.min_range, 0.5);
  EXPECT_DOUBLE_EQ(c.surface.delta_pose, 3.0);
  EXPECT_FALSE(c.tsdf.hasMeshLayer());
  EXPECT_TRUE(c.tsdf.bounds.min.isApprox(Eigen::Vector3d(-10, -10, 0), 1e-5)) << c.tsdf.bounds.min.transpose();
  EXPECT_TRUE(c.tsdf.bounds.max.isApprox(Eigen::Vector3d(10, 10, 12), 1e-5)) << c.tsdf.bounds.max.transpose();
  // 3.5 m out of the -x face (the 3 m ball and half a metre), 2 m up, yaw 0.
  EXPECT_NEAR(c.start.x(), -5.5, 1e-6);
  EXPECT_NEAR(c.start.y(), 0.0, 1e-6);
  EXPECT_NEAR(c.start.z(), 2.0, 1e-6);
  EXPECT_NEAR(c.start.w(), 0.0, 1e-9);
  EXPECT_GT(distanceToMesh(box, c.start.head<3>()), c.start_free_radius);
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
  EXPECT_TRUE(derived(d, "mission/start"));
  EXPECT_NE(d.summary().find("nbv/bounds_min [-10, -10, 0]"), std::string::npos) << d.summary();
  EXPECT_GT(d.map_bytes, 0.0);
}

// Table 1 by the footprint: a 20 m statue-sized scene gets the statue's
// column, a 65 m one the power plant's, each with its mesh layer.
TEST(SceneDefaults, LargerScenesGetTable1sColumns) {
  MissionConfig statue;
  SceneDefaults d;
  ASSERT_TRUE(derive(procedural("statue"), &statue, &d).ok());
  EXPECT_EQ(d.size_class, "statue");
  EXPECT_DOUBLE_EQ(statue.tsdf.voxel_size, 0.15);
  EXPECT_DOUBLE_EQ(statue.camera.min_range, 1.0);
  EXPECT_DOUBLE_EQ(statue.camera.max_range, 5.0);
  EXPECT_DOUBLE_EQ(statue.surface.delta_pose, 3.6);
  EXPECT_DOUBLE_EQ(statue.surface.d_nu, 2.5);
  EXPECT_DOUBLE_EQ(statue.explorer.graph.lambda_tc, 0.17);
  EXPECT_DOUBLE_EQ(statue.explorer.graph.lambda_ic, 0.15);
  EXPECT_DOUBLE_EQ(statue.tsdf.meshVoxelSize(), 0.075);  // config/statue.yaml's layer
  EXPECT_DOUBLE_EQ(statue.tsdf.mesh_truncation, 0.45);
  EXPECT_TRUE(statue.tsdf.mesh_weight_dropoff);
  // No config file: config/statue.yaml's planner settings and UAV too, not its budget.
  EXPECT_EQ(statue.explorer.min_visible, 3);
  EXPECT_EQ(statue.explorer.head_lookahead, 1000);
  EXPECT_DOUBLE_EQ(statue.explorer.head_vertical_scale, 2.0);
  EXPECT_EQ(statue.path.iteration_budget, 3000);
  EXPECT_DOUBLE_EQ(statue.surface.approach_range_fraction, 0.9);
  EXPECT_DOUBLE_EQ(statue.tracker.model.v_max, 1.0);
  EXPECT_DOUBLE_EQ(statue.max_flight_time, MissionConfig().max_flight_time);
  EXPECT_EQ(d.reference_config, kPackage + "/config/statue.yaml");
  EXPECT_TRUE(statue.validate().ok()) << statue.validate().message();
  // The statue's 60 m height is fine: it is the tallest extent.
  MissionConfig plant;
  ASSERT_TRUE(derive(procedural("plant"), &plant, &d).ok());
  EXPECT_EQ(d.size_class, "powerplant");
  EXPECT_DOUBLE_EQ(plant.tsdf.voxel_size, 0.3);
  EXPECT_DOUBLE_EQ(plant.camera.min_range, 1.6);
  EXPECT_DOUBLE_EQ(plant.camera.max_range, 8.0);
  EXPECT_DOUBLE_EQ(plant.surface.delta_pose, 4.7);
  EXPECT_NEAR(plant.tsdf.meshVoxelSize(), 0.1, 1e-12);
  EXPECT_NEAR(plant.tsdf.mesh_truncation, 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(plant.camera.pitch_deg, 5.73);  // the power plant's RotorS mount
  EXPECT_DOUBLE_EQ(plant.surface.camera.pitch_deg, 5.73);
  EXPECT_TRUE(plant.validate().ok()) << plant.validate().message();
  // The take-off pose: outside the plant's box, at a quarter of its 15 m.
  const AlignedBox box = d.scene_box;
  EXPECT_FALSE(box.contains(plant.start.head<3>()));
  EXPECT_NEAR(plant.start.z(), box.min.z() + 3.75, 1e-6);
}

// The bounds and the start follow a scene far from the origin and one
// below z = 0; the floor stays at the ground.
TEST(SceneDefaults, BoundsAndStartFollowTheSceneWhereverItIs) {
  TriangleMesh far = procedural("box");
  far.scaleAndOffset(1.0, Eigen::Vector3d(1500.0, -800.0, 40.0));
  MissionConfig c;
  SceneDefaults d;
  ASSERT_TRUE(derive(far, &c, &d).ok());
  EXPECT_TRUE(c.tsdf.bounds.min.isApprox(Eigen::Vector3d(1490, -810, 40), 1e-6)) << c.tsdf.bounds.min.transpose();
  EXPECT_NEAR(c.start.x(), 1500.0 - 5.5, 1e-4);
  EXPECT_NEAR(c.start.z(), 42.0, 1e-4);
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();

  TriangleMesh below = procedural("sphere");
  below.scaleAndOffset(1.0, Eigen::Vector3d(0.0, 0.0, -7.0));
  c = MissionConfig();
  ASSERT_TRUE(derive(below, &c, &d).ok());
  EXPECT_NEAR(c.tsdf.bounds.min.z(), -7.0, 1e-5);
  EXPECT_NEAR(c.start.z(), -5.0, 1e-5);
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
}

// A key a config gives is kept, the others are derived around it.
TEST(SceneDefaults, GivenKeysAlwaysWin) {
  const TriangleMesh box = procedural("box");
  MissionConfig c;
  SceneDefaults d;
  ASSERT_TRUE(derive(box, &c, &d,
                     "nbv:\n  voxel_size: 0.2\n  bounds_min: [-6, -6, 0]\n  camera: {max_range: 6.0}\n"
                     "mission:\n  start: [0, -5.5, 1.5, 1.5708]\n")
                  .ok());
  EXPECT_DOUBLE_EQ(c.tsdf.voxel_size, 0.2);
  EXPECT_EQ(c.tsdf.bounds.min, Eigen::Vector3d(-6, -6, 0));
  EXPECT_EQ(c.start, Eigen::Vector4d(0, -5.5, 1.5, 1.5708));
  EXPECT_DOUBLE_EQ(c.camera.max_range, 6.0);
  EXPECT_DOUBLE_EQ(c.camera.min_range, 0.5);  // derived
  // bounds_max derived from the given range: 2 m + 6 m.
  EXPECT_TRUE(c.tsdf.bounds.max.isApprox(Eigen::Vector3d(8, 8, 10), 1e-5)) << c.tsdf.bounds.max.transpose();
  EXPECT_FALSE(derived(d, "nbv/voxel_size"));
  EXPECT_FALSE(derived(d, "nbv/bounds_min"));
  EXPECT_FALSE(derived(d, "mission/start"));
  EXPECT_TRUE(derived(d, "nbv/bounds_max"));
  EXPECT_TRUE(d.warnings.empty());
  // Every key of a shipped config given: nothing derived.
  c = MissionConfig();
  ASSERT_TRUE(loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/plant.yaml", &c).ok());
  const MissionConfig shipped = c;
  SceneDefaultsOptions shipped_options;
  shipped_options.config_file = true;
  ASSERT_TRUE(deriveSceneDefaults(procedural("plant"), kPackage, &c, &d, shipped_options).ok());
  EXPECT_FALSE(d.derivedAny()) << d.summary();
  EXPECT_EQ(d.yaml(), "{}\n");
  EXPECT_EQ(c.start, shipped.start);
  EXPECT_EQ(c.tsdf.bounds.max, shipped.tsdf.bounds.max);
  // A given start whose take-off ball reaches the mesh is kept, with a warning.
  c = MissionConfig();
  ASSERT_TRUE(derive(box, &c, &d, "mission:\n  start: [-3, 0, 2, 0]\n").ok());
  EXPECT_EQ(c.start, Eigen::Vector4d(-3, 0, 2, 0));
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_NE(d.warnings[0].find("start_free_radius"), std::string::npos) << d.warnings[0];
}

// Over a config file only the keys that follow the scene's size are lent:
// every shipped config of a built-in scene derives nothing, so it flies as
// it did.
TEST(SceneDefaults, AConfigFileKeepsTheCodesDefaultsBeyondTheSizeKeys) {
  MissionConfig c;
  SceneDefaults d;
  ASSERT_TRUE(derive(procedural("statue"), &c, &d, "mission:\n  path_iterations: 500\n").ok());
  EXPECT_DOUBLE_EQ(c.tsdf.voxel_size, 0.15);
  EXPECT_DOUBLE_EQ(c.camera.max_range, 5.0);
  EXPECT_DOUBLE_EQ(c.surface.approach_range_fraction, 0.9);
  EXPECT_EQ(c.path.iteration_budget, 500);
  EXPECT_EQ(c.explorer.head_lookahead, MissionConfig().explorer.head_lookahead);
  EXPECT_FALSE(derived(d, "mission/min_visible"));
  EXPECT_FALSE(derived(d, "tracker/v_max"));
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
  for (const char* name : {"box", "plant", "statue", "multistorey"}) {
    MissionConfig shipped;
    ASSERT_TRUE(loadMissionConfig(kPackage + "/config/" + name + ".yaml", &shipped).ok()) << name;
    SceneDefaultsOptions from_file;
    from_file.config_file = true;
    ASSERT_TRUE(deriveSceneDefaults(procedural(name), kPackage, &shipped, &d, from_file).ok()) << name;
    EXPECT_FALSE(d.derivedAny()) << name << ": " << d.summary();
  }
}

// The derived keys as YAML for explore_sim.launch: nested sections, a key
// once, loadable by the same reader as a config (and then all given).
TEST(SceneDefaults, TheDerivedYamlLoadsBackAsTheSameConfig) {
  const TriangleMesh statue = procedural("statue");
  MissionConfig c;
  SceneDefaults d;
  ASSERT_TRUE(derive(statue, &c, &d, "nbv:\n  camera: {width: 320}\n").ok());
  const std::string yaml = d.yaml();
  EXPECT_NE(yaml.find("nbv:\n  voxel_size: 0.15\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("  camera:\n    min_range: 1.0\n    max_range: 5.0\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("  mesh_weight_dropoff: true\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("mission:\n  start: ["), std::string::npos) << yaml;
  const std::string file = tempPath("derived.yaml");
  std::ofstream(file) << yaml;
  MissionConfig back;
  ASSERT_TRUE(loadMissionConfig(file, &back).ok());
  EXPECT_DOUBLE_EQ(back.tsdf.voxel_size, c.tsdf.voxel_size);
  EXPECT_DOUBLE_EQ(back.camera.max_range, c.camera.max_range);
  EXPECT_DOUBLE_EQ(back.tsdf.mesh_truncation, c.tsdf.mesh_truncation);
  EXPECT_TRUE(back.tsdf.bounds.min.isApprox(c.tsdf.bounds.min, 1e-5));
  EXPECT_TRUE(back.start.isApprox(c.start, 1e-5));
  SceneDefaults again;
  SceneDefaultsOptions from_file;
  from_file.config_file = true;
  ASSERT_TRUE(deriveSceneDefaults(statue, kPackage, &back, &again, from_file).ok());
  EXPECT_EQ(again.derived.size(), 0u) << again.summary();
}

// From the middles of the faces the mesh is out of the camera's range: two
// 2 m cubes at opposite corners of a 20 m box. The start moves to a corner.
TEST(SceneDefaults, TheStartSeesTheMeshWithinTheCamerasRange) {
  TriangleMesh corners = alignedBox({0, 0, 0}, {2, 2, 3});
  corners.append(alignedBox({18, 18, 0}, {20, 20, 3}));
  MissionConfig c;
  SceneDefaults d;
  ASSERT_TRUE(derive(corners, &c, &d).ok());
  EXPECT_EQ(d.size_class, "statue");  // 5 m range
  const double clear = distanceToMesh(corners, c.start.head<3>());
  EXPECT_GT(clear, c.start_free_radius);
  EXPECT_LE(clear, c.camera.max_range);
  EXPECT_LT(c.start.x(), 0.0);  // the (-x, -y) corner, the first diagonal
  EXPECT_LT(c.start.y(), 0.0);
  EXPECT_NEAR(c.start.w(), std::atan2(10.0 - c.start.y(), 10.0 - c.start.x()), 1e-9);  // facing the centre
  // With bounds too tight for any start outside the box: refused, naming mission/start.
  c = MissionConfig();
  const Status s = derive(corners, &c, &d, "nbv:\n  bounds_min: [-1, -1, 0]\n  bounds_max: [21, 21, 8]\n");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("give mission/start"), std::string::npos) << s.message();
}

TEST(SceneDefaults, RefusesEmptyDegenerateAndTinyMeshes) {
  MissionConfig c;
  SceneDefaults d;
  Status s = derive(TriangleMesh(), &c, &d);
  EXPECT_NE(s.message().find("no triangles"), std::string::npos) << s.message();
  TriangleMesh line;
  line.vertices = {{0, 0, 0}, {5, 0, 0}, {10, 0, 0}};
  line.triangles = {{0, 1, 2}};
  s = derive(line, &c, &d);
  EXPECT_NE(s.message().find("degenerate"), std::string::npos) << s.message();
  TriangleMesh tiny = procedural("box");
  tiny.scaleAndOffset(0.01, Eigen::Vector3d::Zero());  // a 4 m box read as if in metres from centimetres
  s = derive(tiny, &c, &d);
  EXPECT_NE(s.message().find("0.04 m across"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("--scale"), std::string::npos) << s.message();
}

// A tower lying along y (a Y-up model read as Z-up) is refused with the
// --up-axis advice, unless the up axis was given; standing, it is fine.
TEST(SceneDefaults, AMeshLyingOnItsSideIsRefusedUnlessTheUpAxisIsGiven) {
  const TriangleMesh lying = alignedBox({-3, 0, 0}, {3, 30, 6});
  MissionConfig c;
  SceneDefaults d;
  Status s = derive(lying, &c, &d);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("lying on its side"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("--up-axis y"), std::string::npos) << s.message();
  c = MissionConfig();
  EXPECT_TRUE(derive(lying, &c, &d, "depth_sim:\n  scene_up_axis: z\n").ok());
  c = MissionConfig();
  EXPECT_TRUE(derive(alignedBox({-3, -3, 0}, {3, 3, 30}), &c, &d).ok());  // standing up
  c = MissionConfig();
  EXPECT_TRUE(derive(alignedBox({-20, -10, 0}, {20, 10, 9}), &c, &d).ok());  // 40 x 20 x 9: a hall
}

// A 4 m box read as metres from millimetres is 4 km wide: the map would not
// fit. The message says how big, which voxel size fits and suggests
// --scale 0.001; the voxel size it names does fit.
TEST(SceneDefaults, ASceneTooBigForMemoryIsRefusedWithAVoxelSizeThatFits) {
  TriangleMesh mm = procedural("box");
  mm.scaleAndOffset(1000.0, Eigen::Vector3d::Zero());
  MissionConfig c;
  SceneDefaults d;
  Status s = derive(mm, &c, &d);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("4016.0 x 4016.0 x 4008.0 m at 0.3 m voxels"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("--scale 0.001"), std::string::npos) << s.message();
  // A 120 m scene under a 0.5 GB budget: too big at 0.3 m, fits at what it says.
  TriangleMesh hall = alignedBox({0, 0, 0}, {120, 80, 20});
  SceneDefaultsOptions budget;
  budget.memory_budget = 0.5e9;
  c = MissionConfig();
  s = derive(hall, &c, &d, "", budget);
  ASSERT_FALSE(s.ok());
  const size_t at = s.message().find("nbv/voxel_size ");
  ASSERT_NE(at, std::string::npos) << s.message();
  const double fits = std::atof(s.message().c_str() + at + 15);
  EXPECT_GT(fits, 0.3) << s.message();
  MissionConfig coarse;
  coarse.tsdf.voxel_size = fits;
  coarse.given_keys.insert("nbv/voxel_size");
  ASSERT_TRUE(deriveSceneDefaults(hall, kPackage, &coarse, &d, budget).ok());
  EXPECT_LE(d.map_bytes, 0.5e9);
  EXPECT_NEAR(coarse.tsdf.meshVoxelSize(), fits / 3.0, 1e-12);  // the layer follows the given voxel
}

// The command line's scene options count as given.
TEST(SceneDefaults, CommandLineSceneOptionsAreGivenKeys) {
  const char* argv[] = {"tool", "--scene", "x.obj", "--up-axis", "z", "--scale", "0.001"};
  CliArgs args(sceneOptionNames(), {});
  ASSERT_TRUE(args.parse(7, const_cast<char**>(argv)).ok());
  MissionConfig c;
  ASSERT_TRUE(applySceneOptions(args, &c).ok());
  EXPECT_DOUBLE_EQ(c.scene.transform.scale, 0.001);
  EXPECT_EQ(c.given_keys.count("depth_sim/scene_up_axis"), 1u);
  EXPECT_EQ(c.given_keys.count("depth_sim/scene_scale"), 1u);
  EXPECT_EQ(c.given_keys.count("depth_sim/crop_min"), 0u);
}

// The tools: nbv_scene --derive-yaml writes what explore_sim.launch loads,
// nbv_mission prints what it derived first and reports it, and a refused
// scene stops both with one line. Built beside this test (devel/lib/surface_nbv).
struct ToolRun {
  int code = -1;
  std::string out, err;
};

std::string readText(const std::string& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

ToolRun runTool(const std::string& tool, const std::string& arguments) {
  const std::string exe = (std::filesystem::read_symlink("/proc/self/exe").parent_path() / tool).string();
  const std::string out = tempPath(tool + ".out"), err = tempPath(tool + ".err");
  const int status = std::system((exe + " " + arguments + " > " + out + " 2> " + err).c_str());
  ToolRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = readText(out);
  r.err = readText(err);
  return r;
}

TEST(SceneDefaultsTools, NbvSceneAndNbvMissionSayWhatTheyDerivedAndRefuseInOneLine) {
  TriangleMesh box = procedural("box");
  box.scaleAndOffset(1.0, Eigen::Vector3d(20.0, 0.0, -3.0));
  const std::string file = tempPath("tool_box.ply");
  ASSERT_TRUE(saveMesh(box, file).ok());
  const std::string yaml = tempPath("tool_derived/derived_params.yaml");
  std::filesystem::remove_all(tempPath("tool_derived"));
  ToolRun r = runTool("nbv_scene", "--scene " + file + " --derive-yaml " + yaml);
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("derived (small class): nbv/voxel_size 0.1"), std::string::npos) << r.out;
  MissionConfig back;
  ASSERT_TRUE(loadMissionConfig(yaml, &back).ok()) << readText(yaml);
  EXPECT_TRUE(back.tsdf.bounds.min.isApprox(Eigen::Vector3d(10, -10, -3), 1e-6)) << readText(yaml);
  EXPECT_NEAR(back.start.x(), 14.5, 1e-6);

  // A short flight (30 s): the first lines and report.json say what was derived.
  const std::string out = tempPath("tool_mission");
  r = runTool("nbv_mission", "--scene " + file + " --max-flight-time 30 --no-plots --out " + out);
  EXPECT_EQ(r.code, 1) << r.out << r.err;  // stopped by the flight limit, not completed
  const size_t first = r.out.find('\n'), second = r.out.find('\n', first + 1);
  ASSERT_NE(second, std::string::npos) << r.out;
  EXPECT_NE(r.out.substr(0, second).find("derived from the scene (small class, 4.0 m footprint): nbv/voxel_size 0.1"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("mission/start [14.5, 0, -1, 0]"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("outside the map's bounds"), std::string::npos) << r.err;
  const std::string json = readText(out + "/report.json");
  EXPECT_NE(json.find("\"size_class\": \"small\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"nbv/voxel_size\": 0.1,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"mission/start\": ["), std::string::npos) << json;

  // A given --voxel-size wins; a lying mesh is refused in one line, in both tools.
  r = runTool("nbv_scene", "--scene " + file + " --voxel-size 0.2");
  EXPECT_EQ(r.out.find("nbv/voxel_size"), std::string::npos) << r.out;
  const std::string lying = tempPath("tool_lying.stl");
  ASSERT_TRUE(saveMesh(alignedBox({-3, 0, 0}, {3, 30, 6}), lying).ok());
  r = runTool("nbv_mission", "--scene " + lying + " --no-plots --out " + out);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("lying on its side"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = runTool("nbv_scene", "--scene " + lying + " --derive-yaml " + yaml);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("--up-axis y"), std::string::npos) << r.err;
  r = runTool("nbv_mission", "--scene " + lying + " --up-axis z --max-flight-time 1 --no-plots --out " + out);
  EXPECT_EQ(r.err.find("lying on its side"), std::string::npos) << r.err;
}

// --- Whole missions with no config on scene files ---------------------------

struct FileMission {
  const char* what;
  std::string file;
  MeshLoadOptions load;
  double coverage = 0, path_length = 0, flight_min = 0;
};

// Loads `file` as the mission would, derives everything, flies and
// evaluates the reconstruction as nbv_mission does.
void flyWithNoConfig(FileMission* m) {
  MissionConfig c;
  c.scene.scene = m->file;
  c.scene.transform = m->load;
  if (m->load.scale != 1.0) c.given_keys.insert("depth_sim/scene_scale");
  // Repeatable legs (roadmap samples, not wall time), as config/*.yaml ship,
  // and given, so that the small class's reference (box.yaml, none) keeps them.
  c.path.iteration_budget = 3000;
  c.path.time_budget = 30.0;
  c.given_keys.insert({"mission/path_iterations", "mission/path_time_budget"});
  c.max_flight_time = 1800.0;
  TriangleMesh mesh;
  ASSERT_TRUE(loadScene(c.scene, &mesh).ok()) << m->file;
  SceneDefaults d;
  ASSERT_TRUE(deriveSceneDefaults(mesh, kPackage, &c, &d).ok());
  ASSERT_TRUE(c.validate().ok()) << c.validate().message();
  std::unique_ptr<RaycastScene> scene;
  ASSERT_TRUE(RaycastScene::create(mesh, &scene).ok());
  MissionRunner runner(c, *scene);
  const MissionResult r = runner.run();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  MeshExtractor mesher;
  mesher.update(runner.meshMap());
  EvalResult e;
  ASSERT_TRUE(Evaluator(missionEvalConfig(c)).evaluate(mesh, mesher.mesh(), &e).ok());
  m->coverage = e.coverage.coverage();
  m->path_length = r.path_length;
  m->flight_min = r.flight_time / 60.0;
  std::printf("%s (%s, %s class): %s after %.1f min, %.1f m: coverage %.2f %%, wall %.1f s; derived %s\n", m->what,
              m->file.c_str(), d.size_class.c_str(), r.completed ? "completed" : "stopped", m->flight_min,
              m->path_length, 100.0 * m->coverage, r.wall_time, d.summary().c_str());
  EXPECT_TRUE(r.completed) << r.end_reason;
}

TEST(SceneDefaultsMission, ABoxFarFromTheOriginAsObj) {
  TriangleMesh box = procedural("box");
  box.scaleAndOffset(1.0, Eigen::Vector3d(1500.0, -800.0, 40.0));
  FileMission m{"box 1.5 km from the origin", tempPath("far_box.obj"), {}};
  writeObj(box, m.file);
  ASSERT_NO_FATAL_FAILURE(flyWithNoConfig(&m));
  EXPECT_GE(m.coverage, 0.95);
}

TEST(SceneDefaultsMission, ASphereBelowZeroAsPly) {
  TriangleMesh sphere = procedural("sphere");
  sphere.scaleAndOffset(1.0, Eigen::Vector3d(3.0, 2.0, -7.0));
  FileMission m{"sphere below z = 0", tempPath("low_sphere.ply"), {}};
  ASSERT_TRUE(saveMesh(sphere, m.file).ok());
  ASSERT_NO_FATAL_FAILURE(flyWithNoConfig(&m));
  EXPECT_GE(m.coverage, 0.95);
}

// A 12 m cube with a 6 m annex, written in millimetres, read with --scale 0.001:
// the statue class (0.15 m voxels, the 5 m range, a 0.075 m mesh layer).
TEST(SceneDefaultsMission, ABuildingInMillimetresAsStlWithScale) {
  TriangleMesh building = alignedBox({0, 0, 0}, {12, 8, 6});
  building.append(alignedBox({12, 2, 0}, {16, 6, 3}));
  building.scaleAndOffset(1000.0, Eigen::Vector3d::Zero());
  FileMission m{"building in millimetres", tempPath("building_mm.stl"), {}};
  m.load.scale = 0.001;
  ASSERT_TRUE(saveMesh(building, m.file).ok());
  ASSERT_NO_FATAL_FAILURE(flyWithNoConfig(&m));
  EXPECT_GE(m.coverage, 0.95);
}

}  // namespace
