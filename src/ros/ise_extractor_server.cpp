#include "surface_nbv/ros/ise_extractor_server.h"

#include <std_srvs/Trigger.h>
#include <visualization_msgs/MarkerArray.h>

#include "surface_nbv/SurfaceFrontier.h"
#include "surface_nbv/ros/frontier_conversions.h"
#include "surface_nbv/ros/map_conversions.h"

namespace surface_nbv {

IseExtractorServer::IseExtractorServer(ros::NodeHandle nh, const ExtractorConfig& config)
    : nh_(nh),
      config_(config),
      mirror_(config.map),
      builder_(config.surface),
      stats_(nh_, "surface/stats", "ise_extractor", config.stats_period) {
  collision_ = std::make_unique<CollisionMap>(mirror_.map(), config_.collision);
  update_sub_ = nh_.subscribe("tsdf/update", 20, &IseExtractorServer::onUpdate, this);
  frontier_pub_ = nh_.advertise<surface_nbv::SurfaceFrontier>("surface/frontier", 1, true);
  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("surface/markers", 1, true);
  snapshot_client_ = nh_.serviceClient<std_srvs::Trigger>(config_.snapshot_service);
  timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / config_.rate), &IseExtractorServer::onTimer, this);
  ROS_INFO("ise_extractor: voxel %.3f m, delta_pose %.2f m, d_nu %.1f-%.1f m, collision radius %.1f m, %d thread(s)",
           config_.map.voxel_size, config_.surface.delta_pose, config_.surface.d_nu, config_.surface.d_nu_max,
           config_.surface.collision_radius, config_.surface.threads);
}

void IseExtractorServer::onUpdate(const surface_nbv::TsdfUpdateConstPtr& msg) {
  MapUpdate update;
  fromUpdateMsg(*msg, &update);
  const ApplyResult result = mirror_.apply(update);
  stats_.count(std::string("update_") + toString(result));
  if (result == ApplyResult::kApplied) {
    map_time_ = msg->header.stamp;
    return;
  }
  if (result == ApplyResult::kNeedSnapshot) {
    std_srvs::Trigger trigger;
    if (!snapshot_client_.call(trigger)) {
      ROS_WARN_THROTTLE(5.0, "ise_extractor: missed map updates and cannot reach %s for a snapshot",
                        config_.snapshot_service.c_str());
    }
    return;
  }
  if (result != ApplyResult::kIgnored) {
    ROS_WARN_THROTTLE(5.0, "ise_extractor: tsdf/update refused (%s): %s", toString(result),
                      mirror_.lastError().c_str());
  }
}

void IseExtractorServer::onTimer(const ros::WallTimerEvent&) {
  const TsdfMap& map = mirror_.map();
  if (!mirror_.synced() || map.changeCounter() == computed_stamp_) return;
  if (mirror_.resets() != seen_resets_) {
    seen_resets_ = mirror_.resets();
    collision_->rebuild(map);
    builder_.reset();
  } else {
    collision_->update(map);
  }
  Frontier frontier;
  if (Status s = builder_.update(map, *collision_, &frontier); !s) {
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
  header.stamp = map_time_;
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
