// What a mission takes from its scene when no config gives it (issue #39):
// `scripts/explore my_structure.dae` with no --config. ROS-free; nbv_mission
// and nbv_scene (for explore_sim.launch) call the same function, so the
// headless mission and the ROS nodes fly the same derived parameters.
//
// A key is derived only when neither a config file nor a command-line option
// gave it (MissionConfig::given_keys): a given key always wins.
//
// Size class, by the scene's footprint D = the larger of its x and y extents,
// and its reference config, a shipped one (the paper's Table 1 where it applies):
//   D <= 10 m  small       config/box.yaml: 0.1 m voxels, range [0.5, 8] m,
//                          delta_pose 3 m, no mesh layer
//   D <= 30 m  statue      config/statue.yaml: Table 1's Statue column (0.15 m,
//                          [1, 5] m, delta_pose 3.6 m, d_nu 2.5, lambdas 0.17 /
//                          0.15), a 0.075 m mesh layer, level camera
//   D > 30 m   powerplant  config/powerplant.yaml: Table 1's Powerplant column
//                          (0.3 m, [1.6, 8] m, 4.7 m, 2.0, 0.3 / 0.03), a 0.1 m
//                          mesh layer, the camera 5.73 deg down
// The reference lends the keys that follow the scene's size when the user's
// config leaves them out: voxel_size, camera/min_range and max_range,
// delta_pose, d_nu, d_nu_max, lambda_tc, lambda_ic, approach_range_fraction
// and the mesh layer (mesh_voxel_size, mesh_truncation, mesh_weight_dropoff,
// whole or not at all, scaled by a given voxel size's ratio to the
// reference's; mesh_min_weight). With no config file at all it lends every
// key of its nbv, tracker and mission sections (the camera, the UAV's
// limits, the planner's settings the shipped figures were flown with), but
// the scene's own (bounds, start) and the budgets (max_flight_time,
// max_path_length). A config file keeps the code's defaults for the rest,
// so a shipped config flies as it did.
//
// Bounds: the scene's box grown by the camera's max range on every side but
// the floor, which stays at the scene's lowest point (the ground).
// Start: at clamp(H / 4, 2, 4) m above the floor (H the scene's height),
// outside the scene's box, facing the box's centre: beside the middle of the
// -x face first, then +x, -y, +y, then the four corners, each from
// start_free_radius + 0.5 m out, stepping 1 m out up to the bounds; the
// first whose take-off ball (start_free_radius, marked free at take-off)
// stays clear of every triangle, whose UAV (collision radius) stays inside
// the bounds and from which the mesh lies within the camera's range.
//
// Refused, each with one line saying why and what to do:
//  - an empty mesh, one of zero area, one less than 1 m across or a line,
//  - a mesh that looks as if it lay on its side (its longer horizontal extent
//    more than 2.5 times both its other extents), unless the up axis was
//    given (--up-axis y stands a Y-up model upright, --up-axis z keeps it),
//    checked only when the bounds are derived,
//  - a map that does not fit in memory (estimateMapBytes) or in the map's
//    block limit at the voxel size: the message gives the size and the
//    voxel size that would fit.
#pragma once

#include <string>
#include <vector>

#include "surface_nbv/mission/mission_config.h"
#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/util/json_writer.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// One derived key: "nbv/bounds_min" -> "[-10, -10, 0]" (its YAML text).
struct DerivedKey {
  std::string key;
  std::string value;
};

struct SceneDefaults {
  AlignedBox scene_box;     // the scene's triangles' box, metres
  double area_m2 = 0.0;
  std::string size_class;   // "small", "statue" or "powerplant"
  std::string reference_config;  // the class's config file
  std::vector<DerivedKey> derived;  // lent by the reference, then bounds and start
  std::vector<std::string> warnings;
  double map_bytes = 0.0;   // estimateMapBytes of the final config

  bool derivedAny() const { return !derived.empty(); }
  // "nbv/voxel_size 0.15, ..., nbv/bounds_min [..], mission/start [..]; 20 more
  // keys from .../statue.yaml" (the size keys, bounds and start in full), or
  // "nothing (every key given)".
  std::string summary() const;
  // The derived keys as a YAML document (nested maps: nbv: camera: ...),
  // "{}\n" when none; rosparam-loadable.
  std::string yaml() const;
  // "derived": {key: number, [numbers], bool or text} into an open object.
  void writeJson(JsonWriter* json) const;
};

struct SceneDefaultsOptions {
  // A config file was read: only the keys that follow the scene's size are lent.
  bool config_file = false;
  // The memory the maps may take [bytes]; 0: half of this machine's RAM.
  double memory_budget = 0.0;
};

// Derives every key of *config that config->given_keys does not hold from
// `mesh` (the scene as the mission flies it, after its up axis, scale and
// crop) and the reference configs under package_dir/config, then checks the
// map's memory. given_keys stays the user's. The derived config still needs
// validate(). On error *config may be partly derived.
Status deriveSceneDefaults(const TriangleMesh& mesh, const std::string& package_dir, MissionConfig* config,
                           SceneDefaults* out, const SceneDefaultsOptions& options = SceneDefaultsOptions());

// Bytes the mission's maps take at most over config.tsdf.bounds: the planning
// TSDF with every block allocated (8 bytes a voxel, as free space is carved
// wherever the camera looks) plus a byte a voxel for the frontier's states,
// the collision map's 30 bytes a cell, and the mesh layer's blocks within
// its truncation of `area_m2` of surface.
double estimateMapBytes(const MissionConfig& config, double area_m2);

// The scene options of the command line (sceneConfigFromArgs: --scene,
// --up-axis, --scale, --fit-size, --offset, --crop-min, --crop-max) over
// config->scene, each recorded as given (depth_sim/scene_up_axis, ...).
Status applySceneOptions(const CliArgs& args, MissionConfig* config);

// The smallest distance from `p` to a triangle of `mesh` (infinity when empty).
double distanceToMesh(const TriangleMesh& mesh, const Eigen::Vector3d& p);

// A tool's mission config from its command line: --config FILE, else
// config/<--scene>.yaml of the package when it exists (scene default
// "plant"), then the scene options (scene_source.h) on top. *config_file
// gets the file read, "" when none.
Status missionConfigFromArgs(const CliArgs& args, const std::string& package_dir, MissionConfig* config,
                             std::string* config_file);

}  // namespace surface_nbv
