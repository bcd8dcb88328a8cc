// nbv_scene: writes a scene (procedural or a transformed mesh file) to a
// mesh file and prints its size and what a mission would derive from it
// (scene_defaults.h), e.g. for evaluation and rviz.
//
//   nbv_scene --scene plant --out plant.ply
//   nbv_scene --scene powerplant.dae --scale 0.656 --crop-max 1e9,1e9,15 --out pp.ply
//   nbv_scene --scene my.dae [--config YAML] --derive-yaml derived.yaml
//   nbv_scene --list
//
// --derive-yaml FILE writes the keys the config (if any) leaves out, derived
// from the scene, as YAML (explore_sim.launch loads it after the config).
// A scene that cannot be flown is then an error.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "surface_nbv/mission/scene_defaults.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/sim/procedural_scenes.h"
#include "surface_nbv/sim/scene_source.h"

using namespace surface_nbv;

namespace {

int fail(const std::string& message) {
  std::cerr << "nbv_scene: " << message << "\n";
  return 1;
}

Status writeText(const std::string& path, const std::string& text) {
  std::error_code ec;
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  std::ofstream out(path);
  out << text;
  if (!out) return Status::Error("cannot write '" + path + "'");
  return Status::Ok();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> options = sceneOptionNames();
  options.insert(options.end(), {"out", "config", "derive-yaml", "voxel-size"});
  CliArgs args(options, {"list", "help"});
  if (Status s = args.parse(argc, argv); !s) {
    std::cerr << "nbv_scene: " << s.message() << "\n";
    return 2;
  }
  if (args.has("help")) {
    std::cout << "usage: nbv_scene [--scene NAME|FILE] [--up-axis z|y] [--scale S] [--fit-size X,Y,Z] [--offset X,Y,Z]\n"
                 "                 [--crop-min X,Y,Z] [--crop-max X,Y,Z] [--out FILE.ply|FILE.stl]\n"
                 "                 [--config YAML] [--voxel-size M] [--derive-yaml FILE] | --list\n";
    return 0;
  }
  if (args.has("list")) {
    for (const std::string& name : proceduralSceneNames()) std::cout << name << "\n";
    return 0;
  }
  // The scene as a mission would fly it: the config's scene keys, then the options.
  MissionConfig config;
  TriangleMesh mesh;
  Status s;
  if (args.has("config")) s = loadMissionConfig(args.get("config", ""), &config);
  if (s) s = args.getDouble("voxel-size", &config.tsdf.voxel_size);
  if (args.has("voxel-size")) config.given_keys.insert("nbv/voxel_size");
  if (s) s = applySceneOptions(args, &config);
  if (s) s = loadScene(config.scene, &mesh);
  if (s && args.has("out")) s = saveMesh(mesh, args.get("out", ""));
  if (!s) return fail(s.message());
  const AlignedBox b = mesh.bounds();
  std::printf("%s: %zu triangles, %zu vertices, area %.1f m^2, bounds [%.2f %.2f %.2f] - [%.2f %.2f %.2f] m\n",
              config.scene.scene.c_str(), mesh.numTriangles(), mesh.vertices.size(), mesh.area(), b.min.x(),
              b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z());
  if (args.has("out")) std::printf("wrote %s\n", args.get("out", "").c_str());

  SceneDefaults derived;
  SceneDefaultsOptions derive_options;
  derive_options.config_file = args.has("config");
  s = deriveSceneDefaults(mesh, NBV_SOURCE_DIR, &config, &derived, derive_options);
  if (s) s = config.validate();
  if (!s) {
    if (args.has("derive-yaml")) return fail("scene '" + config.scene.scene + "': " + s.message());
    std::printf("a mission could not fly it: %s\n", s.message().c_str());
    return 0;
  }
  std::printf("derived (%s class): %s\n", derived.size_class.c_str(), derived.summary().c_str());
  for (const std::string& w : derived.warnings) std::printf("warning: %s\n", w.c_str());
  if (args.has("derive-yaml")) {
    if (Status w = writeText(args.get("derive-yaml", ""), derived.yaml()); !w) return fail(w.message());
    std::printf("wrote %s\n", args.get("derive-yaml", "").c_str());
  }
  return 0;
}
