// The ise_extractor node: keeps a MapMirror of tsdf/update (asking the
// mapper for a snapshot on a gap), and while the map changes recomputes the
// frontier at `rate` (ISEs, viewpoints, visibility, clusters) and publishes
// surface/frontier, surface/markers and surface/stats.
#pragma once

#include <memory>

#include <ros/ros.h>

#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/extractor_params.h"
#include "surface_nbv/ros/stats_reporter.h"
#include "surface_nbv/surface/frontier_builder.h"

namespace surface_nbv {

class IseExtractorServer {
 public:
  IseExtractorServer(ros::NodeHandle nh, const ExtractorConfig& config);

 private:
  void onUpdate(const surface_nbv::TsdfUpdateConstPtr& msg);
  void onTimer(const ros::WallTimerEvent&);

  ros::NodeHandle nh_;
  ExtractorConfig config_;
  MapMirror mirror_;
  std::unique_ptr<CollisionMap> collision_;
  FrontierBuilder builder_;
  StatsReporter stats_;
  ros::Subscriber update_sub_;
  ros::Publisher frontier_pub_, markers_pub_;
  ros::ServiceClient snapshot_client_;
  ros::WallTimer timer_;
  uint64_t computed_stamp_ = 0;
  uint64_t seen_resets_ = 0;
  ros::Time map_time_;
};

}  // namespace surface_nbv
