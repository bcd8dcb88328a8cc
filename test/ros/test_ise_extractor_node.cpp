// The frontier of the plant after a short flight: non-empty, every viewpoint
// inside the bounds and collision-free (1 m) in the map the test mirrors
// itself, and published every mission/frontier_period s of simulated time
// (the clock runs at 4x).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <vector>

#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "surface_nbv/SurfaceFrontier.h"
#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/map_conversions.h"
#include "surface_nbv/ros/mapper_params.h"

using namespace surface_nbv;

TEST(IseExtractor, FrontierViewpointsAreFreeAndInsideTheBounds) {
  ros::NodeHandle nh;
  // The shared map parameters, read as the nodes read them (one copy, never disagreeing).
  TsdfConfig config;
  const Status shared = loadSharedMapConfig("/nbv", &config);
  ASSERT_TRUE(shared.ok()) << shared.message();
  MapMirror mirror(config);
  std::mutex mutex;
  SurfaceFrontier last;
  size_t frontiers = 0;
  std::vector<double> arrivals;  // ROS (simulated) time of each frontier
  ros::ServiceClient snapshot = nh.serviceClient<std_srvs::Trigger>("tsdf_mapper/request_snapshot");
  ros::Subscriber update_sub = nh.subscribe<TsdfUpdate>("tsdf/update", 50, [&](const TsdfUpdateConstPtr& msg) {
    MapUpdate update;
    fromUpdateMsg(*msg, &update);
    std::lock_guard<std::mutex> l(mutex);
    if (mirror.apply(update) == ApplyResult::kNeedSnapshot) {
      std_srvs::Trigger t;
      snapshot.call(t);
    }
  });
  ros::Subscriber frontier_sub = nh.subscribe<SurfaceFrontier>("surface/frontier", 5, [&](const SurfaceFrontierConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex);
    last = *m;
    ++frontiers;
    arrivals.push_back(ros::Time::now().toSec());
  });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  // 20 s of flight at 4x, then hovering: the map settles.
  ros::WallDuration(14.0).sleep();
  size_t seen_before;
  {
    std::lock_guard<std::mutex> l(mutex);
    seen_before = frontiers;
  }
  ros::WallDuration(4.0).sleep();  // a frontier computed on the settled map

  std::lock_guard<std::mutex> l(mutex);
  ASSERT_GT(frontiers, seen_before) << "no frontier update after the flight";
  // While the map changes, one frontier per frontier_period of simulated
  // time (a wall-clock timer at 1 Hz gives one per 4 s here).
  double period = 0.0;
  ASSERT_TRUE(ros::param::get("/mission/frontier_period", period));
  ASSERT_GE(arrivals.size(), 4u);
  std::vector<double> gaps;
  for (size_t i = 1; i < arrivals.size(); ++i) gaps.push_back(arrivals[i] - arrivals[i - 1]);
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  const double median_gap = gaps[gaps.size() / 2];
  std::printf("%zu frontiers, median gap %.2f s of simulated time (frontier_period %.2f s)\n", arrivals.size(),
              median_gap, period);
  EXPECT_GT(median_gap, 0.75 * period);
  EXPECT_LT(median_gap, 1.5 * period);
  ASSERT_TRUE(mirror.synced());
  EXPECT_GT(last.num_ises, 100u);
  EXPECT_EQ(last.ises.size(), last.num_ises);
  EXPECT_EQ(last.remaining.size(), last.num_remaining);
  std::printf("frontier: %u ISEs (%u in C_rem), %zu viewpoints, %zu clusters\n", last.num_ises, last.num_remaining,
              last.viewpoints.size(), last.clusters.size());
  ASSERT_GE(last.viewpoints.size(), 3u);
  EXPECT_GT(last.clusters.size(), 0u);
  EXPECT_EQ(last.header.frame_id, "world");
  CollisionMap collision(mirror.map(), CollisionConfig());
  size_t free = 0;
  for (const FrontierViewpoint& v : last.viewpoints) {
    const Eigen::Vector3d p(v.pose.position.x, v.pose.position.y, v.pose.position.z);
    EXPECT_TRUE(config.bounds.contains(p)) << p.transpose();
    free += collision.isFree(p, 1.0) ? 1 : 0;
    for (uint32_t i : v.visible_ises) ASSERT_LT(i, last.ises.size());
  }
  EXPECT_EQ(free, last.viewpoints.size()) << "viewpoints within 1 m of an obstacle or unknown space";
  double gain_sum = 0.0;
  for (const FrontierCluster& c : last.clusters) {
    EXPECT_GT(c.gain, 0.0);
    EXPECT_LE(c.gain, 1.0);
    gain_sum += c.gain;
    for (uint32_t i : c.viewpoints) ASSERT_LT(i, last.viewpoints.size());
  }
  EXPECT_GT(gain_sum, 0.0);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_ise_extractor_node");
  return RUN_ALL_TESTS();
}
