// The hand-made world of the nbv_planner rostests: a known free box
// (12 x 12 x 5 m) split by a wall at x = 0, with a gap at y >= 1.5 m or
// closed, and the helpers both tests use to feed the node.
#pragma once

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "surface_nbv/FrontierViewpoint.h"
#include "surface_nbv/SurfaceFrontier.h"
#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/ros/map_conversions.h"

namespace surface_nbv {
namespace planner_test {

inline TsdfConfig mapConfig() {  // as nbv_planner.test
  TsdfConfig c;
  c.voxel_size = 0.25;
  c.w_th = 0.3f;
  c.bounds = AlignedBox(Eigen::Vector3d(-6, -6, 0), Eigen::Vector3d(6, 6, 5));
  return c;
}

inline void buildWorld(TsdfMap* map, bool gap = true) {
  const Eigen::Vector3i& g = map->gridVoxels();
  for (int z = 0; z < g.z(); ++z)
    for (int y = 0; y < g.y(); ++y)
      for (int x = 0; x < g.x(); ++x) {
        const Eigen::Vector3i v(x, y, z);
        const Eigen::Vector3d p = map->voxelCenter(v);
        const bool wall = std::abs(p.x()) < 0.25 && (!gap || p.y() < 1.5);
        TsdfVoxel* voxel = map->allocateVoxel(v);
        voxel->w = 1.0f;
        voxel->phi = wall ? -0.1f : 0.2f;
        map->mutableBlock(TsdfMap::blockOfVoxel(v))->change_stamp = map->beginChange();
      }
}

inline FrontierViewpoint viewpoint(double x, double y, double z, double yaw, std::vector<uint32_t> visible) {
  FrontierViewpoint v;
  v.pose.position.x = x;
  v.pose.position.y = y;
  v.pose.position.z = z;
  v.pose.orientation.w = std::cos(0.5 * yaw);
  v.pose.orientation.z = std::sin(0.5 * yaw);
  v.visible_ises = visible;
  v.unknown_fraction = 1.0;  // faces unseen space: never held back by pool_unknown_below
  return v;
}

// A frontier in world, stamped now: `ises` all in C_ins, `viewpoints`, and
// clusters as (viewpoint indices, gain).
inline SurfaceFrontier frontierOf(const std::vector<Eigen::Vector3d>& ises, std::vector<FrontierViewpoint> viewpoints,
                                  const std::vector<std::pair<std::vector<uint32_t>, double>>& clusters) {
  SurfaceFrontier f;
  f.header.frame_id = "world";
  f.header.stamp = ros::Time::now();
  for (const Eigen::Vector3d& p : ises) {
    geometry_msgs::Point point;
    point.x = p.x();
    point.y = p.y();
    point.z = p.z();
    f.ises.push_back(point);
  }
  f.viewpoints = std::move(viewpoints);
  for (const auto& [members, gain] : clusters) {
    FrontierCluster c;
    c.viewpoints = members;
    c.gain = gain;
    f.clusters.push_back(c);
  }
  f.num_ises = static_cast<uint32_t>(f.ises.size());
  return f;
}

inline bool call(const std::string& name, std::string* message) {
  std_srvs::Trigger t;
  if (!ros::service::call(name, t)) return false;
  *message = t.response.message;
  return t.response.success;
}

// Stands in for tsdf_mapper: `map` whole, latched on tsdf/update, and again
// on every tsdf_mapper/request_snapshot. ok() is false if the map could not
// be packed.
class MapServer {
 public:
  MapServer(ros::NodeHandle& nh, const TsdfMap& map) {
    MapUpdate update;
    ok_ = makeUpdate(map, 0, 1, true, &update).ok();
    std_msgs::Header header;
    header.frame_id = "world";
    header.stamp = ros::Time::now();
    toUpdateMsg(update, header, &msg_);
    pub_ = nh.advertise<TsdfUpdate>("tsdf/update", 1, true);
    snapshot_ = nh.advertiseService("tsdf_mapper/request_snapshot", &MapServer::onSnapshot, this);
    pub_.publish(msg_);
  }
  bool ok() const { return ok_; }

 private:
  bool onSnapshot(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    pub_.publish(msg_);
    res.success = true;
    return true;
  }
  bool ok_ = false;
  TsdfUpdate msg_;
  ros::Publisher pub_;
  ros::ServiceServer snapshot_;
};

// Odometry of a UAV hovering at `p`, yaw 0, in world (stamp it before use).
inline nav_msgs::Odometry hoverOdometry(const Eigen::Vector3d& p) {
  nav_msgs::Odometry odometry;
  odometry.header.frame_id = "world";
  odometry.child_frame_id = "base_link";
  odometry.pose.pose.position.x = p.x();
  odometry.pose.pose.position.y = p.y();
  odometry.pose.pose.position.z = p.z();
  odometry.pose.pose.orientation.w = 1.0;
  return odometry;
}

}  // namespace planner_test
}  // namespace surface_nbv
