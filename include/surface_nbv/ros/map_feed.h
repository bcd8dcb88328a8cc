// A node's own copy of the map: a MapMirror fed from tsdf/update (asking the
// mapper for a snapshot through `snapshot_service` when it missed an update)
// and a CollisionMap kept in step with it on demand. Shared by the nodes that
// consume the map (ise_extractor, nbv_planner). Single-threaded: callbacks
// and refresh() run on the node's spinner.
//
// A missed update costs a whole snapshot (the map, tens of MB on the power
// plant), so the subscriber holds update_queue updates while the node is
// busy, and a gap asks for one snapshot: the updates that arrive before it
// do not ask again until snapshot_retry wall seconds have passed. At 4x a
// request per update (116 in one run) and the snapshots they caused kept the
// planner busy long enough to miss the next update, run after run.
#pragma once

#include <memory>
#include <string>

#include <ros/ros.h>

#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/param_reader.h"
#include "surface_nbv/ros/stats_reporter.h"

namespace surface_nbv {

struct MapFeedConfig {
  std::string snapshot_service = "tsdf_mapper/request_snapshot";
  int update_queue = 100;       // tsdf/update messages held while the node is busy
  double snapshot_retry = 2.0;  // wall s before an unanswered snapshot request is sent again

  Status validate() const;
};

// The keys snapshot_service, update_queue and snapshot_retry.
void readMapFeedKeys(ParamReader* reader, MapFeedConfig* config);

class MapFeed {
 public:
  enum class Refresh { kUnchanged, kUpdated, kRebuilt };

  // Subscribes tsdf/update on `nh`; counts update results in `stats` as update_<result>.
  // `config` must validate().
  MapFeed(ros::NodeHandle& nh, const TsdfConfig& map, const CollisionConfig& collision, const MapFeedConfig& config,
          const std::string& node_name, StatsReporter* stats);

  const MapMirror& mirror() const { return mirror_; }
  const TsdfMap& map() const { return mirror_.map(); }
  const CollisionMap& collision() const { return *collision_; }
  // Header stamp of the last applied update.
  const ros::Time& stamp() const { return stamp_; }
  // ROS time at which the feed last finished work that can hold the node's
  // callbacks back: a snapshot request (a blocking service call) or a
  // snapshot applied. Stale-input checks wait a timeout past it, as past the
  // node's own decisions.
  const ros::Time& workedUntil() const { return worked_until_; }
  // Brings the collision map up to the mirror: kRebuilt after a mirror reset
  // (consumers drop their caches), kUpdated after new blocks.
  Refresh refresh();

 private:
  void onUpdate(const surface_nbv::TsdfUpdateConstPtr& msg);
  void requestSnapshot();

  MapFeedConfig config_;
  std::string node_name_;
  StatsReporter* stats_;
  MapMirror mirror_;
  std::unique_ptr<CollisionMap> collision_;
  ros::Subscriber update_sub_;
  ros::ServiceClient snapshot_client_;
  ros::Time stamp_, worked_until_;
  bool snapshot_asked_ = false;  // a request is out and no snapshot was applied since
  ros::WallTime asked_at_;
  uint64_t seen_resets_ = 0;
  uint64_t collision_stamp_ = 0;
};

}  // namespace surface_nbv
