// Where a simulated scene comes from: a built-in procedural scene by name, or
// a mesh file, with the same scale / offset / crop for both.
#pragma once

#include <string>
#include <vector>

#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/util/cli_args.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct SceneConfig {
  // A procedural scene name (see procedural_scenes.h) or a mesh file path.
  std::string scene = "plant";
  MeshLoadOptions transform;

  Status validate() const;
};

Status loadScene(const SceneConfig& config, TriangleMesh* mesh);

// Command-line form shared by the tools: --scene NAME|FILE, --up-axis z|y,
// --scale S, --fit-size X,Y,Z, --offset X,Y,Z, --crop-min X,Y,Z,
// --crop-max X,Y,Z.
const std::vector<std::string>& sceneOptionNames();
Status sceneConfigFromArgs(const CliArgs& args, SceneConfig* config);

}  // namespace surface_nbv
