// The launched simulation loop: sim-time depth frames of the box scene arrive
// with stamps on the simulated clock, in the camera frame, seeing the box.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <mutex>

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/Image.h>

namespace {

struct Seen {
  std::mutex mutex;
  std::vector<ros::Time> stamps;
  std::vector<double> valid_fraction, min_depth;
  std::vector<std::string> frames;
  ros::Time last_clock;
  int clocks = 0;
};

}  // namespace

TEST(SimLoop, DepthFramesOnSimulatedClockSeeTheBox) {
  ros::NodeHandle nh;
  Seen seen;
  ros::Subscriber clock_sub = nh.subscribe<rosgraph_msgs::Clock>("/clock", 100, [&](const rosgraph_msgs::ClockConstPtr& m) {
    std::lock_guard<std::mutex> l(seen.mutex);
    seen.last_clock = m->clock;
    ++seen.clocks;
  });
  ros::Subscriber image_sub = nh.subscribe<sensor_msgs::Image>("depth/image", 100, [&](const sensor_msgs::ImageConstPtr& m) {
    size_t valid = 0;
    double lo = 1e9;
    for (size_t i = 0; i + 4 <= m->data.size(); i += 4) {
      float z;
      std::memcpy(&z, &m->data[i], 4);
      if (std::isfinite(z)) {
        ++valid;
        lo = std::min<double>(lo, z);
      }
    }
    std::lock_guard<std::mutex> l(seen.mutex);
    seen.stamps.push_back(m->header.stamp);
    seen.frames.push_back(m->header.frame_id);
    seen.valid_fraction.push_back(static_cast<double>(valid) / (m->width * m->height));
    seen.min_depth.push_back(lo);
  });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(60.0);
  while (ros::WallTime::now() < deadline) {
    {
      std::lock_guard<std::mutex> l(seen.mutex);
      if (seen.stamps.size() >= 60) break;
    }
    ros::WallDuration(0.1).sleep();
  }
  std::lock_guard<std::mutex> l(seen.mutex);
  ASSERT_GT(seen.clocks, 10) << "scripted_flight does not publish /clock";
  ASSERT_GE(seen.stamps.size(), 60u) << "too few depth frames";
  for (size_t i = 0; i < seen.stamps.size(); ++i) {
    EXPECT_EQ(seen.frames[i], "camera");
    if (i > 0) {
      EXPECT_GT(seen.stamps[i], seen.stamps[i - 1]);
    }
    // Sim time starts at 1 s, far from wall time.
    EXPECT_LT(seen.stamps[i].toSec(), 1000.0) << "stamp is not simulated time";
    // Flying 4 m from the 4 m box, facing it, it fills a good part of the view.
    EXPECT_GT(seen.valid_fraction[i], 0.2) << "frame " << i;
    EXPECT_GT(seen.min_depth[i], 3.0) << "frame " << i;
    EXPECT_LT(seen.min_depth[i], 6.0) << "frame " << i;
  }
  // 30 Hz of simulated time, at twice real time, for the span of the frames.
  const double span = (seen.stamps.back() - seen.stamps.front()).toSec();
  EXPECT_NEAR((seen.stamps.size() - 1) / span, 30.0, 6.0);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_sim_loop");
  return RUN_ALL_TESTS();
}
