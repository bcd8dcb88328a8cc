#include "surface_nbv/sim/scene_source.h"

#include "surface_nbv/sim/procedural_scenes.h"

namespace surface_nbv {

Status SceneConfig::validate() const {
  if (scene.empty()) return Status::Error("scene expected a procedural scene name or a mesh file path, got ''");
  return transform.validate();
}

Status loadScene(const SceneConfig& config, TriangleMesh* mesh) {
  if (Status s = config.validate(); !s) return s;
  if (!isProceduralScene(config.scene)) return loadMesh(config.scene, config.transform, mesh);
  TriangleMesh built;
  if (Status s = makeProceduralScene(config.scene, &built); !s) return s;
  applyLoadOptions(config.transform, &built);
  if (built.empty()) return Status::Error("scene '" + config.scene + "' has no triangle inside the crop box");
  *mesh = std::move(built);
  return Status::Ok();
}

const std::vector<std::string>& sceneOptionNames() {
  static const std::vector<std::string> names = {"scene", "up-axis", "scale", "fit-size", "offset", "crop-min", "crop-max"};
  return names;
}

Status sceneConfigFromArgs(const CliArgs& args, SceneConfig* config) {
  config->scene = args.get("scene", config->scene);
  config->transform.up_axis = args.get("up-axis", config->transform.up_axis);
  if (Status s = args.getDouble("scale", &config->transform.scale); !s) return s;
  std::vector<double> v;
  if (Status s = args.getDoubles("fit-size", 3, &v); !s) return s;
  if (!v.empty()) config->transform.fit_size = Eigen::Vector3d(v[0], v[1], v[2]);
  v.clear();
  if (Status s = args.getDoubles("offset", 3, &v); !s) return s;
  if (!v.empty()) config->transform.offset = Eigen::Vector3d(v[0], v[1], v[2]);
  v.clear();
  if (Status s = args.getDoubles("crop-min", 3, &v); !s) return s;
  if (!v.empty()) config->transform.crop.min = Eigen::Vector3d(v[0], v[1], v[2]);
  v.clear();
  if (Status s = args.getDoubles("crop-max", 3, &v); !s) return s;
  if (!v.empty()) config->transform.crop.max = Eigen::Vector3d(v[0], v[1], v[2]);
  return config->validate();
}

}  // namespace surface_nbv
