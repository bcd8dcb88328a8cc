// nbv_scene: writes a scene (procedural or a transformed mesh file) to a
// mesh file and prints its size, e.g. for evaluation and rviz.
//
//   nbv_scene --scene plant --out plant.ply
//   nbv_scene --scene powerplant.dae --scale 0.656 --crop-max 1e9,1e9,15 --out pp.ply
//   nbv_scene --list
#include <cstdio>
#include <iostream>

#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/sim/procedural_scenes.h"
#include "surface_nbv/sim/scene_source.h"

using namespace surface_nbv;

int main(int argc, char** argv) {
  std::vector<std::string> options = sceneOptionNames();
  options.push_back("out");
  CliArgs args(options, {"list", "help"});
  if (Status s = args.parse(argc, argv); !s) {
    std::cerr << "nbv_scene: " << s.message() << "\n";
    return 2;
  }
  if (args.has("help")) {
    std::cout << "usage: nbv_scene [--scene NAME|FILE] [--up-axis z|y] [--scale S] [--fit-size X,Y,Z] [--offset X,Y,Z]\n"
                 "                 [--crop-min X,Y,Z] [--crop-max X,Y,Z] [--out FILE.ply|FILE.stl] | --list\n";
    return 0;
  }
  if (args.has("list")) {
    for (const std::string& name : proceduralSceneNames()) std::cout << name << "\n";
    return 0;
  }
  SceneConfig config;
  TriangleMesh mesh;
  Status s = sceneConfigFromArgs(args, &config);
  if (s) s = loadScene(config, &mesh);
  if (s && args.has("out")) s = saveMesh(mesh, args.get("out", ""));
  if (!s) {
    std::cerr << "nbv_scene: " << s.message() << "\n";
    return 1;
  }
  const AlignedBox b = mesh.bounds();
  std::printf("%s: %zu triangles, %zu vertices, area %.1f m^2, bounds [%.2f %.2f %.2f] - [%.2f %.2f %.2f] m\n",
              config.scene.c_str(), mesh.numTriangles(), mesh.vertices.size(), mesh.area(), b.min.x(), b.min.y(),
              b.min.z(), b.max.x(), b.max.y(), b.max.z());
  if (args.has("out")) std::printf("wrote %s\n", args.get("out", "").c_str());
  return 0;
}
