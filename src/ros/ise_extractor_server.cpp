#include "surface_nbv/ros/ise_extractor_server.h"

#include <visualization_msgs/MarkerArray.h>

#include "surface_nbv/SurfaceFrontier.h"
#include "surface_nbv/ros/frontier_conversions.h"

namespace surface_nbv {

IseExtractorServer::IseExtractorServer(ros::NodeHandle nh, const ExtractorConfig& config)
    : nh_(nh),
      config_(config),
      stats_(nh_, "surface/stats", "ise_extractor", config.stats_period),
      feed_(nh_, config.map, config.collision, config.feed, "ise_extractor", &stats_),
      builder_(config.surface) {
  frontier_pub_ = nh_.advertise<surface_nbv::SurfaceFrontier>("surface/frontier", 1, true);
  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("surface/markers", 1, true);
  ROS_INFO("ise_extractor: voxel %.3f m, delta_pose %.2f m, d_nu %.1f-%.1f m, collision radius %.1f m, %d thread(s)",
           config_.map.voxel_size, config_.surface.delta_pose, config_.surface.d_nu, config_.surface.d_nu_max,
           config_.surface.collision_radius, config_.surface.threads);
  if (config_.frontier_period > 0.0) {
    timer_ = nh_.createTimer(ros::Duration(config_.frontier_period), [this](const ros::TimerEvent&) { update(); });
    ROS_INFO("ise_extractor: a frontier every %.2f s of ROS time while the map changes", config_.frontier_period);
  } else {
    wall_timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / config_.rate),
                                      [this](const ros::WallTimerEvent&) { update(); });
    ROS_INFO("ise_extractor: a frontier at %.2f Hz of wall time while the map changes", config_.rate);
  }
}

void IseExtractorServer::update() {
  const TsdfMap& map = feed_.map();
  if (!feed_.mirror().synced() || map.changeCounter() == computed_stamp_) return;
  if (feed_.refresh() == MapFeed::Refresh::kRebuilt) builder_.reset();
  Frontier frontier;
  if (Status s = builder_.update(map, feed_.collision(), &frontier); !s) {
    stats_.count("update_failed");
    ROS_ERROR_THROTTLE(5.0, "ise_extractor: frontier update failed: %s", s.message().c_str());
    return;
  }
  computed_stamp_ = map.changeCounter();
  stats_.recordMs(frontier.stats.total_ms);
  stats_.count("frontiers_published");
  stats_.set("ises", frontier.ises.size());
  stats_.set("remaining", frontier.remaining);
  stats_.set("viewpoints", frontier.viewpoints.size());
  stats_.set("clusters", frontier.clusters.size());
  std_msgs::Header header;
  header.stamp = feed_.stamp();
  header.frame_id = config_.world_frame;
  surface_nbv::SurfaceFrontier msg;
  toFrontierMsg(frontier, header, &msg);
  frontier_pub_.publish(msg);
  if (markers_pub_.getNumSubscribers() > 0) {
    visualization_msgs::MarkerArray markers;
    toFrontierMarkers(frontier, header, config_.map.voxel_size, &markers);
    markers_pub_.publish(markers);
  }
}

}  // namespace surface_nbv
