// How nbv_planner takes in its map and odometry while it is busy:
//  - its MapFeed asks tsdf_mapper for one snapshot per gap in tsdf/update,
//    not one per update that arrives after the gap (before: a blocking
//    service call for each, 116 in one 4x run, and the snapshots they caused
//    kept the node too busy to keep up), and again after snapshot_retry,
//  - LatestOdometry keeps the newest pose on a thread of its own while the
//    node's own callbacks wait (what the planner starts a leg from when the
//    leg is sent after a long decision),
//  - a leg the UAV does not follow (odometry that stays put, as under a
//    tracker that refused the trajectory) is planned again from where the UAV
//    is after off_track_time, without a failure, instead of after the leg's
//    whole duration with one.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <mutex>
#include <string>

#include <nav_msgs/Odometry.h>
#include <trajectory_msgs/MultiDOFJointTrajectory.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "surface_nbv/NodeStats.h"
#include "surface_nbv/PlannerStatus.h"
#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/latest_odometry.h"
#include "surface_nbv/ros/map_conversions.h"

#include "planner_test_world.h"

using namespace surface_nbv;
using namespace surface_nbv::planner_test;

namespace {

// Stands in for tsdf_mapper: publishes what the test says and counts the
// snapshot requests (it does not answer them with a snapshot by itself).
class CountingMapper {
 public:
  explicit CountingMapper(ros::NodeHandle& nh) : map_(mapConfig()) {
    buildWorld(&map_, true);
    pub_ = nh.advertise<TsdfUpdate>("tsdf/update", 50);
    srv_ = nh.advertiseService("tsdf_mapper/request_snapshot", &CountingMapper::onRequest, this);
  }
  bool connected() const { return pub_.getNumSubscribers() > 0; }
  void publish(uint64_t sequence, bool snapshot) {
    MapUpdate update;
    ASSERT_TRUE(makeUpdate(map_, snapshot ? 0 : map_.changeCounter(), sequence, snapshot, &update).ok());
    std_msgs::Header header;
    header.frame_id = "world";
    header.stamp = ros::Time::now();
    TsdfUpdate msg;
    toUpdateMsg(update, header, &msg);
    pub_.publish(msg);
  }
  int requests() const { return requests_; }

 private:
  bool onRequest(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
    ++requests_;
    res.success = true;
    return true;
  }
  TsdfMap map_;
  ros::Publisher pub_;
  ros::ServiceServer srv_;
  std::atomic<int> requests_{0};
};

// The planner's counter `name` on planner/stats (0 before it shows).
class PlannerCounters {
 public:
  explicit PlannerCounters(ros::NodeHandle& nh)
      : sub_(nh.subscribe<NodeStats>("planner/stats", 10, [this](const NodeStatsConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          last_ = *m;
        })) {}
  uint64_t get(const std::string& name) const {
    std::lock_guard<std::mutex> l(mutex_);
    for (const Counter& c : last_.counters)
      if (c.name == name) return c.count;
    return 0;
  }
  // Waits up to `seconds` for get(name) >= value.
  bool waitFor(const std::string& name, uint64_t value, double seconds) const {
    for (ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds); ros::WallTime::now() < end;) {
      if (get(name) >= value) return true;
      ros::WallDuration(0.05).sleep();
    }
    return get(name) >= value;
  }

 private:
  ros::Subscriber sub_;
  mutable std::mutex mutex_;
  NodeStats last_;
};

}  // namespace

TEST(PlannerInputs, AGapAsksForOneSnapshotUntilOneArrivesOrTheRetryIsDue) {
  ros::NodeHandle nh;
  CountingMapper mapper(nh);
  PlannerCounters counters(nh);
  for (int i = 0; i < 200 && !mapper.connected(); ++i) ros::WallDuration(0.1).sleep();
  ASSERT_TRUE(mapper.connected()) << "nbv_planner did not subscribe tsdf/update";
  ros::WallDuration(0.5).sleep();

  mapper.publish(1, true);
  ASSERT_TRUE(counters.waitFor("update_applied", 1, 10.0)) << "the first snapshot was not applied";
  mapper.publish(2, false);
  ASSERT_TRUE(counters.waitFor("update_applied", 2, 10.0));
  EXPECT_EQ(mapper.requests(), 0);

  // Update 3 is lost: 4..8 each find the gap; one request goes out.
  for (uint64_t seq = 4; seq <= 8; ++seq) {
    mapper.publish(seq, false);
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_TRUE(counters.waitFor("update_need_snapshot", 5, 10.0));
  EXPECT_EQ(mapper.requests(), 1) << "one request per gap, not per update (snapshot_retry 1.5 s)";
  EXPECT_EQ(counters.get("snapshot_requests"), 1u);

  // The snapshot comes; the updates after it apply; nothing more is asked.
  mapper.publish(9, true);
  mapper.publish(10, false);
  ASSERT_TRUE(counters.waitFor("update_applied", 4, 10.0));
  EXPECT_EQ(mapper.requests(), 1);

  // A new gap asks at once; an update right after it does not; one after
  // snapshot_retry without a snapshot asks again.
  mapper.publish(12, false);
  ASSERT_TRUE(counters.waitFor("update_need_snapshot", 6, 10.0));
  mapper.publish(13, false);
  ASSERT_TRUE(counters.waitFor("update_need_snapshot", 7, 10.0));
  EXPECT_EQ(mapper.requests(), 2);
  ros::WallDuration(1.7).sleep();
  mapper.publish(14, false);
  ASSERT_TRUE(counters.waitFor("update_need_snapshot", 8, 10.0));
  EXPECT_EQ(mapper.requests(), 3);
}

TEST(PlannerInputs, LatestOdometryKeepsTheNewestValidPoseWhileTheNodeIsBusy) {
  // A node whose callback queue nobody serves stands for one that is busy.
  ros::CallbackQueue never_served;
  ros::NodeHandle busy;
  busy.setCallbackQueue(&never_served);
  LatestOdometry latest(busy, "test_odometry", "world");
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<nav_msgs::Odometry>("test_odometry", 10);
  for (int i = 0; i < 100 && pub.getNumSubscribers() == 0; ++i) ros::WallDuration(0.05).sleep();
  ASSERT_GT(pub.getNumSubscribers(), 0u);
  Eigen::Vector4d pose;
  ros::Time stamp;
  EXPECT_FALSE(latest.get(&pose, &stamp));

  // Only LatestOdometry's own thread takes these.
  nav_msgs::Odometry m = hoverOdometry(Eigen::Vector3d(1.0, 2.0, 3.0));
  for (int i = 1; i <= 5; ++i) {
    m.header.stamp = ros::Time(100.0 + i);
    m.pose.pose.position.x = i;
    pub.publish(m);
    ros::WallDuration(0.05).sleep();
  }
  nav_msgs::Odometry wrong_frame = m;
  wrong_frame.header.frame_id = "map";
  wrong_frame.header.stamp = ros::Time(200.0);
  wrong_frame.pose.pose.position.x = 50.0;
  pub.publish(wrong_frame);
  nav_msgs::Odometry not_finite = m;
  not_finite.header.stamp = ros::Time(201.0);
  not_finite.pose.pose.position.y = std::nan("");
  pub.publish(not_finite);
  nav_msgs::Odometry older = m;
  older.header.stamp = ros::Time(50.0);
  older.pose.pose.position.x = -7.0;
  pub.publish(older);
  ros::WallDuration(0.3).sleep();
  ASSERT_TRUE(latest.get(&pose, &stamp));
  EXPECT_DOUBLE_EQ(pose.x(), 5.0);
  EXPECT_DOUBLE_EQ(pose.y(), 2.0);
  EXPECT_DOUBLE_EQ(pose.z(), 3.0);
  EXPECT_EQ(stamp, ros::Time(105.0));
}

TEST(PlannerInputs, ALegTheUavDoesNotFollowIsPlannedAgainFromWhereItIs) {
  ros::NodeHandle nh;
  CountingMapper mapper(nh);
  PlannerCounters counters(nh);
  for (int i = 0; i < 200 && !mapper.connected(); ++i) ros::WallDuration(0.1).sleep();
  ASSERT_TRUE(mapper.connected());
  ros::WallDuration(0.5).sleep();
  const uint64_t applied = counters.get("update_applied");
  mapper.publish(100, true);
  ASSERT_TRUE(counters.waitFor("update_applied", applied + 1, 10.0));

  struct Plan {
    ros::WallTime received;
    double duration;
    Eigen::Vector3d first;
  };
  std::mutex mutex;
  std::vector<Plan> plans;
  uint32_t leg_failures = 0;
  ros::Subscriber trajectory_sub = nh.subscribe<trajectory_msgs::MultiDOFJointTrajectory>(
      "planner/trajectory", 10, [&](const trajectory_msgs::MultiDOFJointTrajectoryConstPtr& m) {
        if (m->points.size() < 2) return;  // a hold
        const auto& t = m->points.front().transforms.at(0).translation;
        std::lock_guard<std::mutex> l(mutex);
        plans.push_back({ros::WallTime::now(), m->points.back().time_from_start.toSec(), Eigen::Vector3d(t.x, t.y, t.z)});
      });
  ros::Subscriber status_sub = nh.subscribe<PlannerStatus>("planner/status", 20, [&](const PlannerStatusConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex);
    leg_failures = m->leg_failures;
  });
  // One viewpoint behind the wall's gap, some 12 m of path away: a leg of about 25 s.
  ros::Publisher frontier_pub = nh.advertise<SurfaceFrontier>("surface/frontier", 1, true);
  frontier_pub.publish(frontierOf({{2.5, 4.0, 2.5}}, {viewpoint(4.0, 4.0, 2.5, M_PI, {0})}, {{{0}, 0.5}}));
  ros::Publisher odometry_pub = nh.advertise<nav_msgs::Odometry>("odometry", 10);
  const Eigen::Vector3d uav(-4.0, -3.0, 2.5);
  nav_msgs::Odometry odometry = hoverOdometry(uav);
  std::string message;
  // The UAV never moves: 20 Hz odometry at the take-off pose throughout.
  for (int i = 0; i < 800; ++i) {
    odometry.header.stamp = ros::Time::now();
    odometry_pub.publish(odometry);
    if (i == 10) {
      EXPECT_TRUE(call("nbv_planner/start", &message)) << message;
    }
    ros::WallDuration(0.05).sleep();
    std::lock_guard<std::mutex> l(mutex);
    if (plans.size() >= 2) break;
  }
  EXPECT_TRUE(counters.waitFor("legs_off_track", 1, 5.0));
  std::lock_guard<std::mutex> l(mutex);
  ASSERT_GE(plans.size(), 2u) << "the leg nobody flew was not planned again";
  const double gap = (plans[1].received - plans[0].received).toSec();
  EXPECT_GT(plans[0].duration, 15.0) << "the test wants a long leg";
  // 3 m of reference ahead of the UAV at 0.5 m/s, then 2 s off track: about 8 s.
  EXPECT_LT(gap, plans[0].duration - 5.0) << "planned again only when the leg's time ran out";
  EXPECT_NEAR((plans[1].first - uav).norm(), 0.0, 0.3) << "the new leg starts where the UAV is";
  EXPECT_EQ(leg_failures, 0u) << "a leg the UAV did not follow counted against its target";
  std::printf("first leg %.1f s long, planned again after %.1f s\n", plans[0].duration, gap);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_planner_inputs");
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);  // the fake mapper's service and the stats subscriber
  spinner.start();
  return RUN_ALL_TESTS();
}
