#include "surface_nbv/mission/scene_defaults.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include <yaml-cpp/yaml.h>

namespace surface_nbv {
namespace {

// One size class and its reference config (config/<file>).
struct SizeClass {
  const char* name;
  double max_footprint;  // the class holds footprints up to this [m]
  const char* config;
};

// See scene_defaults.h.
const SizeClass kClasses[] = {
    {"small", 10.0, "box.yaml"},
    {"statue", 30.0, "statue.yaml"},
    {"powerplant", std::numeric_limits<double>::infinity(), "powerplant.yaml"},
};

// The sections a reference config lends keys from when no config file was
// read, and its keys that are another scene's own or a budget, never lent.
const char* const kLentSections[] = {"nbv", "tracker", "mission"};
const char* const kNeverLent[] = {"nbv/bounds_min", "nbv/bounds_max", "mission/start", "mission/max_flight_time",
                                  "mission/max_path_length"};
// The keys that follow the scene's size, lent over a config file too.
const char* const kSizeKeys[] = {"nbv/voxel_size", "nbv/camera/min_range", "nbv/camera/max_range", "nbv/delta_pose",
                                 "nbv/d_nu", "nbv/d_nu_max", "nbv/lambda_tc", "nbv/lambda_ic",
                                 "nbv/approach_range_fraction", "nbv/mesh_voxel_size", "nbv/mesh_truncation",
                                 "nbv/mesh_weight_dropoff", "nbv/mesh_min_weight"};
// Lent together or not at all: a mesh layer is these three keys.
const char* const kMeshLayerKeys[] = {"nbv/mesh_voxel_size", "nbv/mesh_truncation", "nbv/mesh_weight_dropoff"};

constexpr double kLyingAspect = 2.5;
constexpr double kMinExtent = 1.0;  // [m]

// To the micrometre: float vertices print as the numbers they stand for.
std::string format(double v) {
  const double rounded = std::round(v * 1e6) / 1e6;
  char text[32];
  std::snprintf(text, sizeof(text), "%.12g", rounded == 0.0 ? 0.0 : rounded);
  return text;
}

std::string formatBytes(double bytes) {
  char text[32];
  if (bytes >= 1e12) std::snprintf(text, sizeof(text), "%.0f TB", bytes / 1e12);
  else if (bytes >= 1e9) std::snprintf(text, sizeof(text), "%.1f GB", bytes / 1e9);
  else std::snprintf(text, sizeof(text), "%.0f MB", bytes / 1e6);
  return text;
}

std::string formatBox(const Eigen::Vector3d& size) {
  char text[96];
  std::snprintf(text, sizeof(text), "%.1f x %.1f x %.1f m", size.x(), size.y(), size.z());
  return text;
}

double machineMemory() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * page : 8e9;
}

// The closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// "a/b/c" -> sections {a, b} and leaf c: the derived keys as nested YAML.
std::string nestedYaml(const std::vector<DerivedKey>& keys) {
  struct Node {
    std::vector<std::string> order;
    std::map<std::string, Node> children;
    std::map<std::string, std::string> leaves;
  };
  Node root;
  for (const DerivedKey& k : keys) {
    Node* node = &root;
    size_t from = 0;
    for (size_t slash; (slash = k.key.find('/', from)) != std::string::npos; from = slash + 1) {
      const std::string section = k.key.substr(from, slash - from);
      if (!node->children.count(section) && !node->leaves.count(section)) node->order.push_back(section);
      node = &node->children[section];
    }
    const std::string leaf = k.key.substr(from);
    if (!node->leaves.count(leaf)) node->order.push_back(leaf);
    node->leaves[leaf] = k.value;
  }
  std::string text;
  const auto write = [&text](const auto& self, const Node& node, const std::string& indent) -> void {
    for (const std::string& name : node.order) {
      if (node.leaves.count(name)) {
        text += indent + name + ": " + node.leaves.at(name) + "\n";
      } else {
        text += indent + name + ":\n";
        self(self, node.children.at(name), indent + "  ");
      }
    }
  };
  write(write, root, "");
  return text;
}

// Every leaf of `node` as "prefix/key" -> its YAML text (flow style).
void collectLeaves(const YAML::Node& node, const std::string& prefix, std::vector<DerivedKey>* out) {
  for (const auto& kv : node) {
    const std::string key = prefix + "/" + kv.first.as<std::string>();
    if (kv.second.IsMap()) {
      collectLeaves(kv.second, key, out);
    } else {
      YAML::Emitter e;
      e << YAML::Flow << kv.second;
      out->push_back({key, e.c_str()});
    }
  }
}

// The keys the reference config lends: those of its sections (with
// size_keys_only, of kSizeKeys) the user's config leaves out, a mesh layer
// whole or not at all, scaled to a given voxel size.
Status lentKeys(const std::string& file, const MissionConfig& c, bool size_keys_only, std::vector<DerivedKey>* lent) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::Exception& e) {
    return Status::Error("cannot read the reference config '" + file + "': " + e.what());
  }
  std::vector<DerivedKey> all;
  for (const char* section : kLentSections) {
    if (root[section] && root[section].IsMap()) collectLeaves(root[section], section, &all);
  }
  const auto given = [&c](const std::string& key) { return c.given_keys.count(key) > 0; };
  bool mesh_layer_given = false;
  for (const char* key : kMeshLayerKeys) mesh_layer_given = mesh_layer_given || given(key);
  double reference_voxel = 0.0;
  for (const DerivedKey& k : all)
    if (k.key == "nbv/voxel_size") reference_voxel = std::atof(k.value.c_str());
  const double voxel_scale = given("nbv/voxel_size") && reference_voxel > 0.0 ? c.tsdf.voxel_size / reference_voxel : 1.0;
  for (DerivedKey k : all) {
    if (given(k.key) || std::count(std::begin(kNeverLent), std::end(kNeverLent), k.key)) continue;
    if (size_keys_only && !std::count(std::begin(kSizeKeys), std::end(kSizeKeys), k.key)) continue;
    const bool mesh_layer_key = std::count(std::begin(kMeshLayerKeys), std::end(kMeshLayerKeys), k.key) > 0;
    if (mesh_layer_key && mesh_layer_given) continue;
    if (mesh_layer_key && k.key != "nbv/mesh_weight_dropoff" && voxel_scale != 1.0) {
      k.value = format(voxel_scale * std::atof(k.value.c_str()));
    }
    lent->push_back(k);
  }
  return Status::Ok();
}

std::string vectorText(const double* v, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + format(v[i]);
  return s + "]";
}

Status checkMesh(const TriangleMesh& mesh, const Eigen::Vector3d& size) {
  if (mesh.empty()) return Status::Error("the scene has no triangles");
  if (!size.allFinite()) return Status::Error("the scene has a vertex that is not finite");
  const double area = mesh.area();
  const double largest = size.maxCoeff();
  if (!(area > 0.0)) return Status::Error("the scene is degenerate: its triangles have no area");
  if (largest < kMinExtent) {
    return Status::Error("the scene is only " + format(largest) + " m across: too small to fly around with a UAV of "
                         "1 m radius (if it is in another unit, give --scale, e.g. --scale 1000 for kilometres)");
  }
  int flat = 0;
  for (int i = 0; i < 3; ++i) flat += size[i] < 1e-3 * largest ? 1 : 0;
  if (flat >= 2) return Status::Error("the scene is degenerate: its triangles lie on a line " + formatBox(size));
  return Status::Ok();
}

// A Y-up model read as Z-up lies on its side: its height along y.
Status checkUpAxis(const Eigen::Vector3d& size) {
  const int longer = size.x() >= size.y() ? 0 : 1;
  const double others = std::max(size[1 - longer], size.z());
  if (size[longer] <= kLyingAspect * others) return Status::Ok();
  const char* axis = longer == 0 ? "x" : "y";
  return Status::Error(std::string("the scene (") + formatBox(size) + ") is more than " + format(kLyingAspect) +
                       " times longer along " + axis + " than high and wide: it looks like a model lying on its side. "
                       "Give --up-axis y (depth_sim/scene_up_axis: y) to stand a Y-up model upright, or --up-axis z "
                       "to keep it as it is");
}

// The voxel size at which estimateMapBytes fits `budget` and the map's block
// limit, in 0.05 m steps from the config's (0 when none up to 100 m does).
double voxelThatFits(const MissionConfig& c, double area, double budget) {
  MissionConfig trial = c;
  const double mesh_ratio = c.tsdf.meshVoxelSize() / c.tsdf.voxel_size;
  const double trunc_ratio = c.tsdf.mesh_truncation / c.tsdf.voxel_size;
  for (double v = std::ceil(c.tsdf.voxel_size / 0.05 + 1e-9) * 0.05; v <= 100.0; v += 0.05) {
    trial.tsdf.voxel_size = v;
    if (c.tsdf.mesh_voxel_size > 0.0) trial.tsdf.mesh_voxel_size = mesh_ratio * v;
    if (c.tsdf.mesh_truncation > 0.0) trial.tsdf.mesh_truncation = trunc_ratio * v;
    const Eigen::Array3d blocks = (trial.tsdf.bounds.size() / (8.0 * v)).array().ceil();
    if (estimateMapBytes(trial, area) <= budget && blocks.prod() <= static_cast<double>(c.tsdf.max_blocks)) return v;
  }
  return 0.0;
}

Status checkMemory(const MissionConfig& c, double area, double budget, SceneDefaults* out) {
  out->map_bytes = estimateMapBytes(c, area);
  const Eigen::Vector3d size = c.tsdf.bounds.size();
  const double blocks = (size / (8.0 * c.tsdf.voxel_size)).array().ceil().prod();
  const bool over_budget = out->map_bytes > budget;
  const bool over_blocks = blocks > static_cast<double>(c.tsdf.max_blocks);
  if (!over_budget && !over_blocks) return Status::Ok();
  std::string why = "the map over " + formatBox(size) + " at " + format(c.tsdf.voxel_size) + " m voxels ";
  why += over_budget ? "needs about " + formatBytes(out->map_bytes) + ", more than the " + formatBytes(budget) +
                           " it may take (half this machine's memory)"
                     : "holds " + format(blocks) + " blocks, more than the map's limit of " +
                           format(static_cast<double>(c.tsdf.max_blocks));
  const double fits = voxelThatFits(c, area, budget);
  if (fits > 0.0) why += ": nbv/voxel_size " + format(fits) + " would fit (--voxel-size " + format(fits) + ")";
  if (size.maxCoeff() > 2000.0) why += "; if the mesh is in millimetres, give --scale 0.001";
  return Status::Error(why);
}

}  // namespace

std::string SceneDefaults::summary() const {
  if (derived.empty()) return "nothing (every key given)";
  std::string s;
  size_t others = 0;
  for (const DerivedKey& k : derived) {
    const bool shown = std::count(std::begin(kSizeKeys), std::end(kSizeKeys), k.key) ||
                       k.key.rfind("nbv/bounds_", 0) == 0 || k.key == "mission/start";
    if (shown) s += (s.empty() ? "" : ", ") + k.key + " " + k.value;
    others += shown ? 0 : 1;
  }
  if (others > 0) s += (s.empty() ? "" : "; ") + std::to_string(others) + " more keys from " + reference_config;
  return s;
}

std::string SceneDefaults::yaml() const {
  if (derived.empty()) return "{}\n";
  return "# Derived from the scene (scene_defaults.h, " + size_class + " class): the keys no config gave.\n" +
         nestedYaml(derived);
}

void SceneDefaults::writeJson(JsonWriter* json) const {
  json->beginObject("derived");
  for (const DerivedKey& k : derived) {
    if (k.value == "true" || k.value == "false") {
      json->value(k.key, k.value == "true");
      continue;
    }
    YAML::Node node;
    try {
      node = YAML::Load(k.value);
    } catch (const YAML::Exception&) {
    }
    double number = 0.0;
    if (node.IsSequence()) {
      json->beginArray(k.key);
      for (const auto& item : node) json->value("", item.as<double>(0.0));
      json->endArray();
    } else if (node.IsScalar() && YAML::convert<double>::decode(node, number)) {
      json->value(k.key, number);
    } else {
      json->value(k.key, k.value);
    }
  }
  json->endObject();
}

double estimateMapBytes(const MissionConfig& c, double area_m2) {
  const Eigen::Vector3d size = c.tsdf.bounds.size();
  const double v = c.tsdf.voxel_size;
  const double blocks = (size / (8.0 * v)).array().ceil().prod();
  const double voxels = blocks * kBlockVoxels;
  const double tsdf = blocks * sizeof(TsdfBlock) + voxels * 1.0;  // + the frontier's byte a voxel
  const double cell = v * std::max(1.0, std::ceil(c.collision.min_cell_size / v - 1e-9));
  const double collision = (size / cell).array().ceil().prod() * 30.0;
  double layer = 0.0;
  if (c.tsdf.hasMeshLayer()) {
    const double block_edge = 8.0 * c.tsdf.meshVoxelSize();
    const double thickness = std::ceil(2.0 * c.tsdf.mesh_truncation / block_edge) + 1.0;
    const double band_blocks = std::min(area_m2 / (block_edge * block_edge) * thickness,
                                        (size / block_edge).array().ceil().prod());
    layer = band_blocks * sizeof(TsdfBlock);
  }
  return tsdf + collision + layer;
}

Status applySceneOptions(const CliArgs& args, MissionConfig* config) {
  const std::pair<const char*, const char*> keys[] = {
      {"scene", "depth_sim/scene"},         {"up-axis", "depth_sim/scene_up_axis"},
      {"scale", "depth_sim/scene_scale"},   {"fit-size", "depth_sim/scene_fit_size"},
      {"offset", "depth_sim/scene_offset"}, {"crop-min", "depth_sim/crop_min"},
      {"crop-max", "depth_sim/crop_max"}};
  for (const auto& [option, key] : keys) {
    if (args.has(option)) config->given_keys.insert(key);
  }
  return sceneConfigFromArgs(args, &config->scene);
}

double distanceToMesh(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  double best2 = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                          c = mesh.vertices[t[2]].cast<double>();
    // The triangle's box first: most triangles are farther than the best.
    const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
    const Eigen::Vector3d gap = (lo - p).cwiseMax(p - hi).cwiseMax(Eigen::Vector3d::Zero());
    if (gap.squaredNorm() >= best2) continue;
    best2 = std::min(best2, (closestOnTriangle(p, a, b, c) - p).squaredNorm());
  }
  return std::sqrt(best2);
}

Status deriveSceneDefaults(const TriangleMesh& mesh, const std::string& package_dir, MissionConfig* config,
                           SceneDefaults* out, const SceneDefaultsOptions& options) {
  *out = SceneDefaults();
  MissionConfig& c = *config;
  const AlignedBox box = mesh.bounds();
  const Eigen::Vector3d size = box.size();
  out->scene_box = box;
  if (Status s = checkMesh(mesh, size); !s) return s;
  out->area_m2 = mesh.area();
  const auto given = [&c](const std::string& key) { return c.given_keys.count(key) > 0; };
  if (!(given("nbv/bounds_min") && given("nbv/bounds_max")) && !given("depth_sim/scene_up_axis")) {
    if (Status s = checkUpAxis(size); !s) return s;
  }

  // The size class's reference config lends the keys the user's leaves out.
  const double footprint = std::max(size.x(), size.y());
  const SizeClass* k = &kClasses[0];
  while (footprint > k->max_footprint) ++k;
  out->size_class = k->name;
  out->reference_config = package_dir + "/config/" + k->config;
  std::vector<DerivedKey> lent;
  if (Status s = lentKeys(out->reference_config, c, options.config_file, &lent); !s) return s;
  const std::set<std::string> user_given = c.given_keys;
  if (!lent.empty()) {
    if (Status s = loadMissionConfigText(nestedYaml(lent), out->reference_config, &c); !s) return s;
  }
  c.given_keys = user_given;
  out->derived = lent;

  // The bounds: the box and the camera's range around it, the floor at the ground.
  const double margin = c.camera.max_range;
  if (!given("nbv/bounds_min")) {
    c.tsdf.bounds.min = Eigen::Vector3d(box.min.x() - margin, box.min.y() - margin, box.min.z());
    out->derived.push_back({"nbv/bounds_min", vectorText(c.tsdf.bounds.min.data(), 3)});
  }
  if (!given("nbv/bounds_max")) {
    c.tsdf.bounds.max = box.max + Eigen::Vector3d::Constant(margin);
    out->derived.push_back({"nbv/bounds_max", vectorText(c.tsdf.bounds.max.data(), 3)});
  }
  const AlignedBox& bounds = c.tsdf.bounds;

  const double radius = c.start_free_radius;
  const double uav = c.path.collision_radius;
  if (!given("mission/start")) {
    const double z = bounds.min.z() + std::max(std::clamp(0.25 * size.z(), 2.0, 4.0), uav + 0.5);
    const Eigen::Vector3d centre = box.center();
    const double s = std::sqrt(0.5);
    // Directions out of the box: the faces' middles, then the corners.
    const Eigen::Vector2d dirs[] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-s, -s}, {s, -s}, {-s, s}, {s, s}};
    bool found = false;
    for (double out_by = radius + 0.5; !found && out_by <= std::max(margin, 1.0) + 1e-9; out_by += 1.0) {
      for (const Eigen::Vector2d& dir : dirs) {
        // From the box's face (its corner for a diagonal) out along dir.
        Eigen::Vector3d p(dir.x() < 0 ? box.min.x() : dir.x() > 0 ? box.max.x() : centre.x(),
                          dir.y() < 0 ? box.min.y() : dir.y() > 0 ? box.max.y() : centre.y(), z);
        p.head<2>() += out_by * dir;
        const Eigen::Vector3d lo = p.array() - uav, hi = p.array() + uav;
        if (!bounds.contains(lo) || !bounds.contains(hi)) continue;
        const double clear = distanceToMesh(mesh, p);
        if (clear <= radius || clear <= uav || clear > c.camera.max_range) continue;
        c.start = Eigen::Vector4d(p.x(), p.y(), p.z(), std::atan2(centre.y() - p.y(), centre.x() - p.x()));
        out->derived.push_back({"mission/start", vectorText(c.start.data(), 4)});
        found = true;
        break;
      }
    }
    if (!found) {
      return Status::Error("no take-off pose outside the scene's box " + formatBox(size) + " keeps a " +
                           format(radius) + " m take-off ball clear of the mesh within the camera's " +
                           format(c.camera.max_range) + " m of it: give mission/start (and start_free_radius)");
    }
  } else if (radius > 0.0 && distanceToMesh(mesh, c.start.head<3>()) <= radius) {
    out->warnings.push_back("the take-off ball (mission/start_free_radius " + format(radius) +
                            " m) reaches the scene's mesh: the map starts with part of the structure free");
  }

  const double budget = options.memory_budget > 0.0 ? options.memory_budget : 0.5 * machineMemory();
  return checkMemory(c, out->area_m2, budget, out);
}

Status missionConfigFromArgs(const CliArgs& args, const std::string& package_dir, MissionConfig* config,
                             std::string* config_file) {
  *config_file = args.get("config", defaultConfigFile(package_dir, args.get("scene", "plant")));
  if (!config_file->empty()) {
    if (Status s = loadMissionConfig(*config_file, config); !s) return s;
  }
  return applySceneOptions(args, config);
}

}  // namespace surface_nbv
