// depth_sim as a real sensor (depth_sim_real.test, issue #40): 16UC1
// millimetres, 0 for dropouts, stereo noise around the true depth, a new
// draw every frame.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <mutex>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <tf2_ros/transform_broadcaster.h>
#include <Eigen/Geometry>

namespace {

TEST(DepthSimReal, PublishesNoisyMillimetresWithDropouts) {
  ros::NodeHandle nh;
  std::mutex mutex;
  std::vector<sensor_msgs::Image> images;
  ros::Subscriber sub = nh.subscribe<sensor_msgs::Image>("depth/image", 20, [&](const sensor_msgs::ImageConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex);
    images.push_back(*m);
  });
  // The camera at (-6, 0, 2) looking along +x at the box's face x = -2: 4 m.
  tf2_ros::TransformBroadcaster broadcaster;
  ros::WallTimer timer = nh.createWallTimer(ros::WallDuration(0.01), [&](const ros::WallTimerEvent&) {
    geometry_msgs::TransformStamped tf;
    tf.header.stamp = ros::Time::now();
    tf.header.frame_id = "world";
    tf.child_frame_id = "camera";
    tf.transform.translation.x = -6.0;
    tf.transform.translation.z = 2.0;
    const Eigen::Quaterniond q((Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished());
    tf.transform.rotation.w = q.w();
    tf.transform.rotation.x = q.x();
    tf.transform.rotation.y = q.y();
    tf.transform.rotation.z = q.z();
    broadcaster.sendTransform(tf);
  });
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    {
      std::lock_guard<std::mutex> l(mutex);
      if (images.size() >= 3) break;
    }
    ros::WallDuration(0.05).sleep();
  }
  std::lock_guard<std::mutex> l(mutex);
  ASSERT_GE(images.size(), 3u);
  // A 100 x 100 window in the middle sees the face at 4 m (sigma 0.16 m).
  std::vector<std::vector<uint16_t>> windows;
  for (size_t k = images.size() - 2; k < images.size(); ++k) {
    const sensor_msgs::Image& img = images[k];
    ASSERT_EQ(img.encoding, "16UC1");
    ASSERT_EQ(img.step, 2u * img.width);
    std::vector<uint16_t> w;
    size_t zeros = 0;
    double sum = 0.0, sum2 = 0.0;
    size_t n = 0;
    for (int r = 190; r < 290; ++r) {
      for (int c = 270; c < 370; ++c) {
        uint16_t mm;
        std::memcpy(&mm, &img.data[r * img.step + 2 * c], 2);
        w.push_back(mm);
        if (mm == 0) {
          ++zeros;
          continue;
        }
        const double e = 0.001 * mm - 4.0;
        ASSERT_LT(std::abs(e), 6 * 0.16) << mm;
        sum += e;
        sum2 += e * e;
        ++n;
      }
    }
    EXPECT_NEAR(static_cast<double>(zeros) / w.size(), 0.2, 0.02);  // binomial sd 0.4 %
    const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(sd, 0.16, 0.016);
    EXPECT_NEAR(mean, 0.0, 0.02);
    windows.push_back(w);
  }
  // Two frames at the same pose draw different noise.
  size_t differing = 0;
  for (size_t i = 0; i < windows[0].size(); ++i) differing += windows[0][i] != windows[1][i] ? 1 : 0;
  EXPECT_GT(differing, windows[0].size() / 2);
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_depth_sim_real");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
