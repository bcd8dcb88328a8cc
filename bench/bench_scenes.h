// Scenes shared by the benchmarks: a built-in procedural scene by name, or
// "powerplant", the shared Gazebo power plant set up as in the paper (and as
// config/powerplant.yaml): scaled by 0.656, clipped above z = 15 m.
// NBV_SOURCE_DIR is the repository root, defined by the build.
#pragma once

#include <string>

#include "surface_nbv/sim/scene_source.h"

namespace surface_nbv {

inline std::string powerplantPath() { return std::string(NBV_SOURCE_DIR) + "/../shared/scenes/powerplant.dae"; }

inline SceneConfig benchSceneConfig(const std::string& name) {
  SceneConfig config;
  config.scene = name;
  if (name == "powerplant") {
    config.scene = powerplantPath();
    config.transform.scale = 0.656;
    config.transform.crop.max.z() = 15.0;
  }
  return config;
}

}  // namespace surface_nbv
