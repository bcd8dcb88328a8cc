// nbv_planner while it plans longer than its odometry timeout: a closed wall
// splits the world and every viewpoint of the frontier lies behind it, so
// each decision spends its whole ~leg_time_budget (2.5 s of wall time; the
// path planner alone would take 30 s) and hovers naming the budget. The
// test publishes odometry all along; odometry that queued while the node
// planned must not read as stale (odometry_timeout 0.3 s): no hold with
// reason odometry_stale. Before the grace, the first tick after each
// decision found the last processed odometry older than the timeout.
#include <gtest/gtest.h>

#include <mutex>
#include <string>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include "surface_nbv/PlannerStatus.h"
#include "surface_nbv/SurfaceFrontier.h"
#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/map_conversions.h"

#include "planner_test_world.h"

using namespace surface_nbv;
using namespace surface_nbv::planner_test;

namespace {

// Two clusters, both behind the closed wall from the UAV at (-4, -3, 2.5).
SurfaceFrontier frontierBehindTheWall() {
  return frontierOf({{0.375, -3.0, 2.5}, {0.375, 3.0, 2.5}},
                    {viewpoint(2.5, -3.0, 2.5, M_PI, {0}), viewpoint(2.5, 3.0, 2.5, M_PI, {1})},
                    {{{0}, 0.5}, {{1}, 0.5}});
}

}  // namespace

TEST(NbvPlannerBusy, OdometryThatQueuedWhileThePlannerWorkedIsNotStale) {
  ros::NodeHandle nh;
  TsdfMap map(mapConfig());
  buildWorld(&map, false);
  MapServer map_server(nh, map);
  ASSERT_TRUE(map_server.ok());

  std::mutex mutex;
  size_t budget_holds = 0, stale_holds = 0, statuses = 0;
  std::string last_message;
  ros::Subscriber status_sub =
      nh.subscribe<PlannerStatus>("planner/status", 50, [&](const PlannerStatusConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        ++statuses;
        last_message = m->state + " " + m->reason + ": " + m->message;
        if (m->reason == "odometry_stale") ++stale_holds;
        if (m->message.find("leg_time_budget") != std::string::npos) ++budget_holds;
      });
  ros::Publisher frontier_pub = nh.advertise<SurfaceFrontier>("surface/frontier", 1, true);
  ros::Publisher odometry_pub = nh.advertise<nav_msgs::Odometry>("odometry", 10);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ASSERT_TRUE(ros::service::waitForService("nbv_planner/start", ros::Duration(20.0)));

  nav_msgs::Odometry odometry = hoverOdometry(Eigen::Vector3d(-4.0, -3.0, 2.5));
  std::string message;
  // 20 Hz odometry throughout; a new frontier every second starts a decision
  // whenever the node is free. Three budget holds take about 8 s.
  for (int i = 0; i < 600; ++i) {
    odometry.header.stamp = ros::Time::now();
    odometry_pub.publish(odometry);
    if (i == 10) {
      EXPECT_TRUE(call("nbv_planner/start", &message)) << message;
    }
    if (i >= 10 && i % 20 == 10) frontier_pub.publish(frontierBehindTheWall());
    ros::WallDuration(0.05).sleep();
    std::lock_guard<std::mutex> l(mutex);
    if (budget_holds >= 3) break;
  }
  std::lock_guard<std::mutex> l(mutex);
  EXPECT_GE(budget_holds, 3u) << "decisions did not spend leg_time_budget; last status: " << last_message;
  EXPECT_EQ(stale_holds, 0u) << "odometry that queued while the node planned was taken as stale; last status: "
                             << last_message;
  std::printf("%zu statuses, %zu budget holds, %zu odometry_stale\n", statuses, budget_holds, stale_holds);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_nbv_planner_busy");
  return RUN_ALL_TESTS();
}
