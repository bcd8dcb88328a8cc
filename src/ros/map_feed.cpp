#include "surface_nbv/ros/map_feed.h"

#include <cmath>

#include <std_srvs/Trigger.h>

#include "surface_nbv/ros/map_conversions.h"

namespace surface_nbv {

Status MapFeedConfig::validate() const {
  if (snapshot_service.empty()) return Status::Error("snapshot_service expected a service name");
  if (update_queue < 1 || update_queue > 10000) return Status::Error("update_queue expected in [1, 10000]");
  if (!(snapshot_retry > 0.0) || !std::isfinite(snapshot_retry)) return Status::Error("snapshot_retry expected > 0 s");
  return Status::Ok();
}

void readMapFeedKeys(ParamReader* reader, MapFeedConfig* config) {
  reader->get("snapshot_service", &config->snapshot_service);
  reader->get("update_queue", &config->update_queue);
  reader->get("snapshot_retry", &config->snapshot_retry);
}

MapFeed::MapFeed(ros::NodeHandle& nh, const TsdfConfig& map, const CollisionConfig& collision,
                 const MapFeedConfig& config, const std::string& node_name, StatsReporter* stats)
    : config_(config), node_name_(node_name), stats_(stats), mirror_(map) {
  collision_ = std::make_unique<CollisionMap>(mirror_.map(), collision);
  update_sub_ = nh.subscribe("tsdf/update", static_cast<uint32_t>(config_.update_queue), &MapFeed::onUpdate, this);
  snapshot_client_ = nh.serviceClient<std_srvs::Trigger>(config_.snapshot_service);
}

void MapFeed::onUpdate(const surface_nbv::TsdfUpdateConstPtr& msg) {
  MapUpdate update;
  fromUpdateMsg(*msg, &update);
  const ApplyResult result = mirror_.apply(update);
  stats_->count(std::string("update_") + toString(result));
  if (result == ApplyResult::kApplied) {
    stamp_ = msg->header.stamp;
    if (update.snapshot) {
      snapshot_asked_ = false;
      worked_until_ = ros::Time::now();
    }
  } else if (result == ApplyResult::kNeedSnapshot) {
    requestSnapshot();
  } else if (result != ApplyResult::kIgnored) {
    ROS_WARN_THROTTLE(5.0, "%s: tsdf/update refused (%s): %s", node_name_.c_str(), toString(result),
                      mirror_.lastError().c_str());
  }
}

void MapFeed::requestSnapshot() {
  const ros::WallTime now = ros::WallTime::now();
  if (snapshot_asked_ && (now - asked_at_).toSec() < config_.snapshot_retry) return;  // one is on its way
  snapshot_asked_ = true;
  asked_at_ = now;
  stats_->count("snapshot_requests");
  std_srvs::Trigger trigger;
  if (!snapshot_client_.call(trigger)) {
    ROS_WARN_THROTTLE(5.0, "%s: missed map updates and cannot reach %s for a snapshot", node_name_.c_str(),
                      config_.snapshot_service.c_str());
  }
  worked_until_ = ros::Time::now();
}

MapFeed::Refresh MapFeed::refresh() {
  const TsdfMap& map = mirror_.map();
  Refresh result = Refresh::kUnchanged;
  if (mirror_.resets() != seen_resets_) {
    seen_resets_ = mirror_.resets();
    collision_->rebuild(map);
    result = Refresh::kRebuilt;
  } else if (map.changeCounter() != collision_stamp_) {
    collision_->update(map);
    result = Refresh::kUpdated;
  }
  collision_stamp_ = map.changeCounter();
  return result;
}

}  // namespace surface_nbv
