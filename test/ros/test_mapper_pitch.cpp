// tsdf_mapper's check of the image frames against camera/pitch_deg: the box
// flight's camera is level (camera_mount reads a namespace that says so), the
// mapper is told 5.73 degrees down; tsdf/stats must flag the mismatch once
// enough frames are in, and the frames are still fused.
#include <gtest/gtest.h>

#include <mutex>

#include <ros/ros.h>

#include "surface_nbv/NodeStats.h"

namespace {

// The counter's value, or -1 when tsdf/stats does not carry it.
int64_t counter(const surface_nbv::NodeStats& s, const std::string& name) {
  for (const auto& c : s.counters) {
    if (c.name == name) return static_cast<int64_t>(c.count);
  }
  return -1;
}

}  // namespace

TEST(TsdfMapperPitch, StatsFlagACameraPitchedOtherwiseThanConfigured) {
  ros::NodeHandle nh, priv("~");
  double mapper_pitch = 0.0, mount_pitch = 1.0;
  ASSERT_TRUE(nh.getParam("/nbv/camera/pitch_deg", mapper_pitch));
  ASSERT_TRUE(nh.getParam("/level_camera/camera/pitch_deg", mount_pitch));
  ASSERT_GT(std::abs(mapper_pitch - mount_pitch), 2.0) << "the launch file must make them differ";
  std::mutex mutex;
  surface_nbv::NodeStats stats;
  ros::Subscriber sub = nh.subscribe<surface_nbv::NodeStats>("tsdf/stats", 1, [&](const surface_nbv::NodeStatsConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex);
    stats = *m;
  });
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(60.0);
  bool flagged = false;
  int64_t frames = 0;
  while (ros::WallTime::now() < deadline && !flagged) {
    ros::WallDuration(0.5).sleep();
    std::lock_guard<std::mutex> l(mutex);
    frames = counter(stats, "frames_integrated");
    flagged = counter(stats, "camera_pitch_mismatch") == 1;
  }
  EXPECT_TRUE(flagged) << "no mismatch flagged after " << frames << " frames";
  EXPECT_GE(frames, 30) << "flagged before the monitor's 30 frames";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_mapper_pitch");
  return RUN_ALL_TESTS();
}
