#include "surface_nbv/mission/scene_defaults.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace surface_nbv {
namespace {

// One size class: the camera, the voxel and Table 1's planning parameters.
struct SizeClass {
  const char* name;
  double max_footprint;     // the class holds footprints up to this [m]
  double voxel_size, min_range, max_range, delta_pose, d_nu, d_nu_max, lambda_tc, lambda_ic;
  double mesh_voxel_divisor;  // 0: no mesh layer
};

// See scene_defaults.h; the rows are config/box.yaml and Table 1's columns.
const SizeClass kClasses[] = {
    {"small", 10.0, 0.1, 0.5, 8.0, 3.0, 2.0, 5.0, 0.3, 0.03, 0.0},
    {"statue", 30.0, 0.15, 1.0, 5.0, 3.6, 2.5, 5.0, 0.17, 0.15, 2.0},
    {"powerplant", std::numeric_limits<double>::infinity(), 0.3, 1.6, 8.0, 4.7, 2.0, 5.0, 0.3, 0.03, 3.0},
};

constexpr double kMeshTruncationVoxels = 6.0;  // 0.6 m at 0.1 m, 0.45 m at 0.075 m
constexpr double kLyingAspect = 2.5;
constexpr double kMinExtent = 1.0;             // [m]

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

// Derives into *config and records what it did.
class Deriver {
 public:
  Deriver(MissionConfig* config, SceneDefaults* out) : c_(*config), out_(*out) {}

  bool given(const std::string& key) const { return c_.given_keys.count(key) > 0; }

  // Sets *field to `v` unless `key` was given.
  template <typename T>
  void set(const std::string& key, T* field, double v) {
    if (given(key)) return;
    *field = static_cast<T>(v);
    out_.derived.push_back({key, {v}, false});
  }
  void setBool(const std::string& key, bool* field, bool v) {
    if (given(key)) return;
    *field = v;
    out_.derived.push_back({key, {v ? 1.0 : 0.0}, true});
  }
  void setVector(const std::string& key, Eigen::Vector3d* field, const Eigen::Vector3d& v) {
    if (given(key)) return;
    *field = v;
    out_.derived.push_back({key, {v.x(), v.y(), v.z()}, false});
  }
  void setStart(const Eigen::Vector4d& v) {
    c_.start = v;
    out_.derived.push_back({"mission/start", {v[0], v[1], v[2], v[3]}, false});
  }

 private:
  MissionConfig& c_;
  SceneDefaults& out_;
};

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

std::string DerivedKey::yamlValue() const {
  if (boolean) return values.at(0) != 0.0 ? "true" : "false";
  if (values.size() == 1) return format(values[0]);
  std::string s = "[";
  for (size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + format(values[i]);
  return s + "]";
}

std::string SceneDefaults::summary() const {
  if (derived.empty()) return "nothing (every key given)";
  std::string s;
  for (const DerivedKey& k : derived) s += (s.empty() ? "" : ", ") + k.key + " " + k.yamlValue();
  return s;
}

std::string SceneDefaults::yaml() const {
  if (derived.empty()) return "{}\n";
  // Nested maps in first-seen order of each path's sections.
  struct Node {
    std::vector<std::string> order;
    std::map<std::string, Node> children;
    std::map<std::string, std::string> leaves;
  };
  Node root;
  for (const DerivedKey& k : derived) {
    Node* node = &root;
    size_t from = 0;
    for (size_t slash; (slash = k.key.find('/', from)) != std::string::npos; from = slash + 1) {
      const std::string section = k.key.substr(from, slash - from);
      if (!node->children.count(section) && !node->leaves.count(section)) node->order.push_back(section);
      node = &node->children[section];
    }
    const std::string leaf = k.key.substr(from);
    if (!node->leaves.count(leaf)) node->order.push_back(leaf);
    node->leaves[leaf] = k.yamlValue();
  }
  std::string text = "# Derived from the scene by nbv_scene --derive-yaml (scene_defaults.h): the keys no config gave.\n";
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

Status deriveSceneDefaults(const TriangleMesh& mesh, MissionConfig* config, SceneDefaults* out,
                           const SceneDefaultsOptions& options) {
  *out = SceneDefaults();
  MissionConfig& c = *config;
  const AlignedBox box = mesh.bounds();
  const Eigen::Vector3d size = box.size();
  out->scene_box = box;
  if (Status s = checkMesh(mesh, size); !s) return s;
  out->area_m2 = mesh.area();
  Deriver d(config, out);
  const bool bounds_given = d.given("nbv/bounds_min") && d.given("nbv/bounds_max");
  if (!bounds_given && !d.given("depth_sim/scene_up_axis")) {
    if (Status s = checkUpAxis(size); !s) return s;
  }

  // The camera, the voxels and Table 1 by the footprint.
  const double footprint = std::max(size.x(), size.y());
  const SizeClass* k = &kClasses[0];
  while (footprint > k->max_footprint) ++k;
  out->size_class = k->name;
  d.set("nbv/voxel_size", &c.tsdf.voxel_size, k->voxel_size);
  d.set("nbv/camera/min_range", &c.camera.min_range, k->min_range);
  d.set("nbv/camera/max_range", &c.camera.max_range, k->max_range);
  d.set("nbv/delta_pose", &c.surface.delta_pose, k->delta_pose);
  d.set("nbv/d_nu", &c.surface.d_nu, k->d_nu);
  d.set("nbv/d_nu_max", &c.surface.d_nu_max, k->d_nu_max);
  d.set("nbv/lambda_tc", &c.explorer.graph.lambda_tc, k->lambda_tc);
  d.set("nbv/lambda_ic", &c.explorer.graph.lambda_ic, k->lambda_ic);
  if (k->mesh_voxel_divisor > 0.0 && !d.given("nbv/mesh_truncation") && !d.given("nbv/mesh_voxel_size")) {
    const double mesh_voxel = c.tsdf.voxel_size / k->mesh_voxel_divisor;
    d.set("nbv/mesh_voxel_size", &c.tsdf.mesh_voxel_size, mesh_voxel);
    d.set("nbv/mesh_truncation", &c.tsdf.mesh_truncation, kMeshTruncationVoxels * mesh_voxel);
    d.setBool("nbv/mesh_weight_dropoff", &c.tsdf.mesh_weight_dropoff, true);
    d.set("nbv/mesh_min_weight", &c.tsdf.mesh_min_weight, 0.0);
  }
  c.surface.camera = c.camera;
  c.explorer.gaze.camera = c.camera;

  // The bounds: the box and the camera's range around it, the floor at the ground.
  const double margin = c.camera.max_range;
  d.setVector("nbv/bounds_min", &c.tsdf.bounds.min,
              Eigen::Vector3d(box.min.x() - margin, box.min.y() - margin, box.min.z()));
  d.setVector("nbv/bounds_max", &c.tsdf.bounds.max, box.max + Eigen::Vector3d::Constant(margin));
  const AlignedBox& bounds = c.tsdf.bounds;

  const double radius = c.start_free_radius;
  const double uav = c.path.collision_radius;
  if (!d.given("mission/start")) {
    const double z = bounds.min.z() + std::max(std::clamp(0.25 * size.z(), 2.0, 4.0), uav + 0.5);
    const Eigen::Vector3d centre = box.center();
    const double s = std::sqrt(0.5);
    // Directions out of the box: the faces' middles, then the corners.
    const Eigen::Vector2d dirs[] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-s, -s}, {s, -s}, {-s, s}, {s, s}};
    bool found = false;
    const double reach = std::max(margin, 1.0);
    for (double out_by = radius + 0.5; !found && out_by <= reach + 1e-9; out_by += 1.0) {
      for (const Eigen::Vector2d& dir : dirs) {
        // From the box's face (its corner for a diagonal) out along dir.
        Eigen::Vector3d p(dir.x() < 0 ? box.min.x() : dir.x() > 0 ? box.max.x() : centre.x(),
                          dir.y() < 0 ? box.min.y() : dir.y() > 0 ? box.max.y() : centre.y(), z);
        p.head<2>() += out_by * dir;
        const Eigen::Vector3d lo = p.array() - uav, hi = p.array() + uav;
        if (!bounds.contains(lo) || !bounds.contains(hi)) continue;
        const double clear = distanceToMesh(mesh, p);
        if (clear <= radius || clear <= uav || clear > c.camera.max_range) continue;
        d.setStart(Eigen::Vector4d(p.x(), p.y(), p.z(), std::atan2(centre.y() - p.y(), centre.x() - p.x())));
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

}  // namespace surface_nbv
