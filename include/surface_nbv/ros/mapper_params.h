// Parameters of tsdf_mapper. Shared keys (voxel_size, w_th, bounds_min,
// bounds_max, camera/min_range, camera/max_range) come from the shared
// namespace, so the mapper, extractor and planner cannot disagree; the rest
// are the node's own (~).
#pragma once

#include <string>

#include "surface_nbv/config/config_keys.h"
#include "surface_nbv/map/tsdf_config.h"
#include "surface_nbv/ros/param_reader.h"
#include "surface_nbv/sensor/depth_camera.h"

namespace surface_nbv {

struct MapperConfig {
  std::string shared_namespace = kSharedNamespace;
  std::string mission_namespace = "/mission";  // invalid_pixels, start_free_radius (then ~)
  TsdfConfig tsdf;
  CameraConfig camera;            // only min_range / max_range are used (intrinsics come from CameraInfo)
  std::string world_frame = "world";
  std::string input = "image";    // "image" (depth/image + depth/camera_info) or "points" (depth/points)
  double update_rate = 2.0;       // Hz of tsdf/update
  double mesh_rate = 0.5;         // Hz of tsdf/mesh (0 = never)
  double stats_period = 1.0;      // s
  std::string map_directory = "/tmp/surface_nbv_maps";
  int max_pending_frames = 10;    // frames waiting for their transform
  // Depth messages roscpp holds while the mapper is busy; beyond it the oldest
  // are dropped unseen. Bag replay wants more than a live camera (map_bag.launch).
  int input_queue = 5;
  double tf_wait = 0.5;           // s a frame may wait for its transform
  double start_free_radius = 0.0; // m: unknown voxels this close to the first sensor pose become free (0 = off)
  double autosave_period = 0.0;   // s (wall) between autosaves to map_directory/autosave_{0,1}.tsdf; 0 = off
  bool resume = false;            // at start, load the newest valid autosave (after a crash and respawn)

  Status validate() const;
};

// The shared map parameters of namespace `ns` (e.g. "/nbv"), as every node
// reads them, for tests and tools that mirror the map.
Status loadSharedMapConfig(const std::string& ns, TsdfConfig* map);
// (The keys themselves: readTsdfKeys of config/config_keys.h, as nbv_mission reads them.)

Status loadMapperParams(const ros::NodeHandle& priv, MapperConfig* config);

}  // namespace surface_nbv
