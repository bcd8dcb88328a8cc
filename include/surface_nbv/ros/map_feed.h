// A node's own copy of the map: a MapMirror fed from tsdf/update (asking the
// mapper for a snapshot through `snapshot_service` when it missed an update)
// and a CollisionMap kept in step with it on demand. Shared by the nodes that
// consume the map (ise_extractor, nbv_planner). Single-threaded: callbacks
// and refresh() run on the node's spinner.
#pragma once

#include <memory>
#include <string>

#include <ros/ros.h>

#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/stats_reporter.h"

namespace surface_nbv {

class MapFeed {
 public:
  enum class Refresh { kUnchanged, kUpdated, kRebuilt };

  // Subscribes tsdf/update on `nh`; counts update results in `stats` as update_<result>.
  MapFeed(ros::NodeHandle& nh, const TsdfConfig& map, const CollisionConfig& collision,
          const std::string& snapshot_service, const std::string& node_name, StatsReporter* stats);

  const MapMirror& mirror() const { return mirror_; }
  const TsdfMap& map() const { return mirror_.map(); }
  const CollisionMap& collision() const { return *collision_; }
  // Header stamp of the last applied update.
  const ros::Time& stamp() const { return stamp_; }
  // Brings the collision map up to the mirror: kRebuilt after a mirror reset
  // (consumers drop their caches), kUpdated after new blocks.
  Refresh refresh();

 private:
  void onUpdate(const surface_nbv::TsdfUpdateConstPtr& msg);

  std::string node_name_, snapshot_service_;
  StatsReporter* stats_;
  MapMirror mirror_;
  std::unique_ptr<CollisionMap> collision_;
  ros::Subscriber update_sub_;
  ros::ServiceClient snapshot_client_;
  ros::Time stamp_;
  uint64_t seen_resets_ = 0;
  uint64_t collision_stamp_ = 0;
};

}  // namespace surface_nbv
