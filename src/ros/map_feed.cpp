#include "surface_nbv/ros/map_feed.h"

#include <std_srvs/Trigger.h>

#include "surface_nbv/ros/map_conversions.h"

namespace surface_nbv {

MapFeed::MapFeed(ros::NodeHandle& nh, const TsdfConfig& map, const CollisionConfig& collision,
                 const std::string& snapshot_service, const std::string& node_name, StatsReporter* stats)
    : node_name_(node_name), snapshot_service_(snapshot_service), stats_(stats), mirror_(map) {
  collision_ = std::make_unique<CollisionMap>(mirror_.map(), collision);
  update_sub_ = nh.subscribe("tsdf/update", 20, &MapFeed::onUpdate, this);
  snapshot_client_ = nh.serviceClient<std_srvs::Trigger>(snapshot_service);
}

void MapFeed::onUpdate(const surface_nbv::TsdfUpdateConstPtr& msg) {
  MapUpdate update;
  fromUpdateMsg(*msg, &update);
  const ApplyResult result = mirror_.apply(update);
  stats_->count(std::string("update_") + toString(result));
  if (result == ApplyResult::kApplied) {
    stamp_ = msg->header.stamp;
  } else if (result == ApplyResult::kNeedSnapshot) {
    std_srvs::Trigger trigger;
    if (!snapshot_client_.call(trigger)) {
      ROS_WARN_THROTTLE(5.0, "%s: missed map updates and cannot reach %s for a snapshot", node_name_.c_str(),
                        snapshot_service_.c_str());
    }
  } else if (result != ApplyResult::kIgnored) {
    ROS_WARN_THROTTLE(5.0, "%s: tsdf/update refused (%s): %s", node_name_.c_str(), toString(result),
                      mirror_.lastError().c_str());
  }
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
