// The ise_extractor node: keeps a MapMirror of tsdf/update (asking the
// mapper for a snapshot on a gap), and while the map changes recomputes the
// frontier every frontier_period s of ROS time (else at `rate` per wall
// second): ISEs, viewpoints, visibility, clusters; publishes surface/frontier,
// surface/markers and surface/stats.
#pragma once

#include <memory>

#include <ros/ros.h>

#include "surface_nbv/ros/extractor_params.h"
#include "surface_nbv/ros/map_feed.h"
#include "surface_nbv/ros/stats_reporter.h"
#include "surface_nbv/surface/frontier_builder.h"

namespace surface_nbv {

class IseExtractorServer {
 public:
  IseExtractorServer(ros::NodeHandle nh, const ExtractorConfig& config);

 private:
  void update();

  ros::NodeHandle nh_;
  ExtractorConfig config_;
  StatsReporter stats_;
  MapFeed feed_;
  FrontierBuilder builder_;
  ros::Publisher frontier_pub_, markers_pub_;
  ros::Timer timer_;            // frontier_period > 0 (ROS time)
  ros::WallTimer wall_timer_;   // else
  uint64_t computed_stamp_ = 0;
};

}  // namespace surface_nbv
