// nbv_planner on a hand-made world: a known free box (12 x 12 x 5 m) split by
// a wall at x = 0 with a gap at y >= 1.5 m, a frontier of 3 clusters on both
// sides of the wall and a UAV hovering at (-4, -3, 2.5). The trajectory must
// stay inside the bounds and >= 1 m from obstacles (checked on a CollisionMap
// of the same map), with increasing times; ~stop / ~start / ~replan answer
// success in any state and ~stop sends a hold trajectory at the UAV's pose.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>
#include <visualization_msgs/MarkerArray.h>

#include "surface_nbv/PlannerStatus.h"
#include "surface_nbv/SurfaceFrontier.h"
#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/map_conversions.h"

#include "planner_test_world.h"

using namespace surface_nbv;
using namespace surface_nbv::planner_test;

namespace {

SurfaceFrontier makeFrontier() {
  return frontierOf({{-0.375, -3, 2.5}, {0.375, -3, 2.5}, {-0.375, -1, 2.5}, {0.375, -1, 2.5}, {-0.375, 1, 2.5},
                     {0.375, 1, 2.5}},
                    {viewpoint(-2.5, -2.0, 2.5, 0.0, {0, 2}), viewpoint(-2.5, 0.0, 2.5, 0.0, {2, 4}),
                     viewpoint(2.5, -3.0, 2.5, M_PI, {1}), viewpoint(2.5, -1.0, 2.5, M_PI, {3}),
                     viewpoint(3.0, 3.5, 2.5, -M_PI / 2, {5})},
                    {{{0, 1}, 0.5}, {{2, 3}, 1.0 / 3.0}, {{4}, 1.0 / 6.0}});
}

}  // namespace

TEST(NbvPlanner, TrajectoryIsFreeInsideTheBoundsAndTimed) {
  ros::NodeHandle nh;
  const TsdfConfig config = mapConfig();
  TsdfMap map(config);
  buildWorld(&map);
  const CollisionMap collision(map, CollisionConfig());
  const Eigen::Vector3d uav(-4.0, -3.0, 2.5);
  ASSERT_TRUE(collision.isFree(uav, 1.2));

  std::mutex mutex;
  trajectory_msgs::MultiDOFJointTrajectory last_plan, last_hold;
  size_t plans = 0, holds = 0;
  ros::Subscriber trajectory_sub = nh.subscribe<trajectory_msgs::MultiDOFJointTrajectory>(
      "planner/trajectory", 10, [&](const trajectory_msgs::MultiDOFJointTrajectoryConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        if (m->points.size() > 1) {
          last_plan = *m;
          ++plans;
        } else {
          last_hold = *m;
          ++holds;
        }
      });
  // The markers are built only for a subscriber (this one): the leg and the
  // roadmap, which comes again only after kRoadmapMarkerPeriod (5 s of wall)
  // once it has edges. Arrival times: no two roadmaps closer than 4.5 s, and
  // at least one array arrives within 4.5 s of a roadmap (which must then
  // leave it out), however fast the machine.
  constexpr double kRoadmapGap = 4.5;
  size_t leg_points = 0, roadmap_points = 0, arrays_in_period = 0;
  double min_roadmap_gap = std::numeric_limits<double>::infinity();
  ros::WallTime last_roadmap;
  ros::Subscriber markers_sub = nh.subscribe<visualization_msgs::MarkerArray>(
      "planner/markers", 10, [&](const visualization_msgs::MarkerArrayConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        const ros::WallTime now = ros::WallTime::now();
        const bool after_roadmap = roadmap_points > 0;
        const double since = after_roadmap ? (now - last_roadmap).toSec() : 0.0;
        if (after_roadmap && since < kRoadmapGap) ++arrays_in_period;
        for (const visualization_msgs::Marker& marker : m->markers) {
          if (marker.ns == "leg") leg_points = std::max(leg_points, marker.points.size());
          if (marker.ns != "roadmap") continue;
          if (after_roadmap) min_roadmap_gap = std::min(min_roadmap_gap, since);
          roadmap_points = std::max(roadmap_points, marker.points.size());
          last_roadmap = now;
        }
      });
  MapServer map_server(nh, map);
  ASSERT_TRUE(map_server.ok());
  ros::Publisher frontier_pub = nh.advertise<SurfaceFrontier>("surface/frontier", 1, true);
  ros::Publisher odometry_pub = nh.advertise<nav_msgs::Odometry>("odometry", 10);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ASSERT_TRUE(ros::service::waitForService("nbv_planner/start", ros::Duration(20.0)));

  std::string message;
  EXPECT_TRUE(call("nbv_planner/stop", &message)) << message;   // stopped already
  EXPECT_TRUE(call("nbv_planner/replan", &message)) << message;  // while stopped
  frontier_pub.publish(makeFrontier());
  nav_msgs::Odometry odometry = hoverOdometry(uav);
  auto publishOdometry = [&] {
    odometry.header.stamp = ros::Time::now();
    odometry_pub.publish(odometry);
  };
  for (int i = 0; i < 10; ++i) {
    publishOdometry();
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_TRUE(call("nbv_planner/start", &message)) << message;
  EXPECT_TRUE(call("nbv_planner/start", &message)) << message;  // while running
  for (int i = 0; i < 200; ++i) {
    publishOdometry();
    ros::WallDuration(0.05).sleep();
    std::lock_guard<std::mutex> l(mutex);
    if (plans > 0) break;
  }
  {
    std::lock_guard<std::mutex> l(mutex);
    ASSERT_GT(plans, 0u) << "no planner/trajectory";
    EXPECT_EQ(last_plan.header.frame_id, "world");
    EXPECT_FALSE(last_plan.header.stamp.isZero());
    const auto& first = last_plan.points.front().transforms.at(0).translation;
    EXPECT_NEAR((Eigen::Vector3d(first.x, first.y, first.z) - uav).norm(), 0.0, 1e-6);
    double previous = -1.0;
    for (const auto& point : last_plan.points) {
      ASSERT_EQ(point.transforms.size(), 1u);
      const auto& t = point.transforms[0].translation;
      const Eigen::Vector3d p(t.x, t.y, t.z);
      EXPECT_TRUE(config.bounds.contains(p)) << p.transpose();
      EXPECT_TRUE(collision.isFree(p, 1.0)) << p.transpose() << " is " << collision.distance(p) << " m from obstacles";
      EXPECT_GT(point.time_from_start.toSec(), previous);
      previous = point.time_from_start.toSec();
    }
    const auto& last = last_plan.points.back().transforms.at(0).translation;
    double to_viewpoint = 1e9;  // the trajectory ends at a configuration of the tour
    for (const FrontierViewpoint& v : makeFrontier().viewpoints) {
      to_viewpoint = std::min(to_viewpoint, std::hypot(last.x - v.pose.position.x, last.y - v.pose.position.y,
                                                       last.z - v.pose.position.z));
    }
    EXPECT_LT(to_viewpoint, 1e-6);
    std::printf("trajectory: %zu points, %.1f s, ends at (%.2f, %.2f, %.2f)\n", last_plan.points.size(), previous,
                last.x, last.y, last.z);
  }
  for (int i = 0; i < 40; ++i) {
    ros::WallDuration(0.05).sleep();
    std::lock_guard<std::mutex> l(mutex);
    if (leg_points > 1 && roadmap_points > 0) break;
  }
  {
    std::lock_guard<std::mutex> l(mutex);
    EXPECT_GT(leg_points, 1u) << "planner/markers showed no leg";
    EXPECT_GT(roadmap_points, 0u) << "planner/markers showed no roadmap";
  }
  for (int i = 0; i < 60; ++i) {  // a few more arrays: one per decision, which a new frontier brings
    if (i % 10 == 0) frontier_pub.publish(makeFrontier());
    publishOdometry();
    ros::WallDuration(0.05).sleep();
    std::lock_guard<std::mutex> l(mutex);
    if (arrays_in_period >= 2) break;
  }
  {
    std::lock_guard<std::mutex> l(mutex);
    EXPECT_GE(arrays_in_period, 1u) << "no planner/markers within " << kRoadmapGap << " s of a roadmap";
    EXPECT_GE(min_roadmap_gap, kRoadmapGap) << "the roadmap was sent again within its 5 s period";
  }
  EXPECT_TRUE(call("nbv_planner/replan", &message)) << message;  // while running
  EXPECT_TRUE(call("nbv_planner/stop", &message)) << message;
  EXPECT_TRUE(call("nbv_planner/stop", &message)) << message;
  for (int i = 0; i < 40; ++i) {
    ros::WallDuration(0.05).sleep();
    std::lock_guard<std::mutex> l(mutex);
    if (holds > 0) break;
  }
  std::lock_guard<std::mutex> l(mutex);
  ASSERT_GT(holds, 0u) << "~stop sent no hold trajectory";
  ASSERT_EQ(last_hold.points.size(), 1u);
  const auto& hold = last_hold.points[0].transforms.at(0).translation;
  EXPECT_NEAR((Eigen::Vector3d(hold.x, hold.y, hold.z) - uav).norm(), 0.0, 1e-6);
}

// Runs after TrajectoryIsFreeInsideTheBoundsAndTimed (the planner is STOPPED,
// the map and a frontier are latched): every service in every state, hovering
// on stale odometry, DONE on a complete frontier, a new mission after DONE.
TEST(NbvPlanner, ServicesAnswerInEveryStateStaleOdometryHoversCompleteFrontierEnds) {
  ros::NodeHandle nh;
  std::mutex mutex;
  PlannerStatus status;
  ros::Subscriber status_sub =
      nh.subscribe<PlannerStatus>("planner/status", 10, [&](const PlannerStatusConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        status = *m;
      });
  ros::Publisher frontier_pub = nh.advertise<SurfaceFrontier>("surface/frontier", 1, true);
  ros::Publisher odometry_pub = nh.advertise<nav_msgs::Odometry>("odometry", 10);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  nav_msgs::Odometry odometry;
  odometry.header.frame_id = "world";
  odometry.pose.pose.position.x = -4.0;
  odometry.pose.pose.position.y = -3.0;
  odometry.pose.pose.position.z = 2.5;
  odometry.pose.pose.orientation.w = 1.0;
  auto waitFor = [&](const std::string& state, bool feed_odometry, double seconds) {
    for (int i = 0; i < seconds * 20; ++i) {
      if (feed_odometry) {
        odometry.header.stamp = ros::Time::now();
        odometry_pub.publish(odometry);
      }
      ros::WallDuration(0.05).sleep();
      std::lock_guard<std::mutex> l(mutex);
      if (status.state == state) return true;
    }
    return false;
  };
  const std::vector<std::string> services{"nbv_planner/start", "nbv_planner/stop", "nbv_planner/replan"};
  std::string message;
  // STOPPED: every service answers.
  ASSERT_TRUE(waitFor("STOPPED", false, 5.0)) << status.state;
  EXPECT_TRUE(call("nbv_planner/replan", &message)) << message;
  EXPECT_TRUE(call("nbv_planner/stop", &message)) << message;
  // RUNNING, then odometry stops: HOVERING with the reason.
  EXPECT_TRUE(call("nbv_planner/start", &message)) << message;
  ASSERT_TRUE(waitFor("RUNNING", true, 5.0)) << status.state;
  ASSERT_TRUE(waitFor("HOVERING", false, 5.0)) << status.state << " " << status.reason;
  EXPECT_EQ(status.reason, "odometry_stale");
  EXPECT_TRUE(call("nbv_planner/replan", &message)) << message;
  EXPECT_TRUE(call("nbv_planner/start", &message)) << message;
  EXPECT_NE(message.find("already HOVERING"), std::string::npos) << message;
  // Odometry comes back: RUNNING again.
  ASSERT_TRUE(waitFor("RUNNING", true, 5.0)) << status.state << " " << status.reason;
  // A frontier with no ISE of C_ins: DONE, with the reason.
  SurfaceFrontier complete = makeFrontier();
  complete.header.stamp = ros::Time::now();
  complete.viewpoints.clear();
  complete.clusters.clear();
  for (uint32_t i = 0; i < complete.ises.size(); ++i) complete.remaining.push_back(i);
  frontier_pub.publish(complete);
  ASSERT_TRUE(waitFor("DONE", true, 10.0)) << status.state << " " << status.reason;
  EXPECT_EQ(status.reason, "complete");
  EXPECT_EQ(status.ises_remaining, complete.ises.size());
  EXPECT_TRUE(call("nbv_planner/replan", &message)) << message;
  EXPECT_TRUE(call("nbv_planner/stop", &message)) << message;
  EXPECT_NE(message.find("mission already over"), std::string::npos) << message;
  // ~start after DONE: a new mission on the current map.
  EXPECT_TRUE(call("nbv_planner/start", &message)) << message;
  EXPECT_NE(message.find("new mission"), std::string::npos) << message;
  EXPECT_TRUE(waitFor("RUNNING", true, 5.0) || status.state == "DONE") << status.state;
  for (const std::string& s : services) EXPECT_TRUE(call(s, &message)) << s << ": " << message;
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_nbv_planner_node");
  return RUN_ALL_TESTS();
}
