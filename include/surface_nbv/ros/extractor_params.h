// Parameters of ise_extractor. From the shared namespace: voxel_size, w_th,
// bounds_min, bounds_max, camera/*, delta_pose, d_nu, d_nu_max (Table 1 of the
// paper, one copy for every node); from the mission namespace the default of
// frontier_period; the rest are the node's own (~).
#pragma once

#include <string>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/tsdf_config.h"
#include "surface_nbv/ros/map_feed.h"
#include "surface_nbv/ros/param_reader.h"
#include "surface_nbv/surface/surface_config.h"

namespace surface_nbv {

struct ExtractorConfig {
  std::string shared_namespace = kSharedNamespace;
  TsdfConfig map;                 // voxel size, w_th and bounds of the mirrored map
  SurfaceConfig surface;
  CollisionConfig collision;
  std::string world_frame = "world";
  std::string mission_namespace = "/mission";  // frontier_period's default comes from there
  // s of ROS time (the simulated clock under /use_sim_time) between frontier
  // updates while the map changes: the headless runner's mission/frontier_period,
  // so that a mission at any real-time factor gets its frontiers as often per
  // second of flight. 0: `rate` per wall second instead.
  double frontier_period = 0.0;
  double rate = 1.0;              // Hz of wall time, with frontier_period 0
  MapFeedConfig feed;             // snapshot_service, update_queue, snapshot_retry (map_feed.h)
  double stats_period = 1.0;

  Status validate() const;
};

Status loadExtractorParams(const ros::NodeHandle& priv, ExtractorConfig* config);

}  // namespace surface_nbv
