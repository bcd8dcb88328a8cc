// Regression tests for what the message fuzz tests and the libFuzzer targets
// of fuzz/ found (docs/reliability.md lists them). Each case is the smallest
// form of a failing input.
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>

#include "surface_nbv/ros/depth_conversions.h"
#include "surface_nbv/ros/mpc_tracker_server.h"

using namespace surface_nbv;

namespace {

sensor_msgs::PointCloud2 xyzCloud(uint32_t x, uint32_t y, uint32_t z, uint32_t point_step) {
  sensor_msgs::PointCloud2 msg;
  const char* names[3] = {"x", "y", "z"};
  const uint32_t offsets[3] = {x, y, z};
  for (int i = 0; i < 3; ++i) {
    sensor_msgs::PointField f;
    f.name = names[i];
    f.offset = offsets[i];
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    msg.fields.push_back(f);
  }
  msg.point_step = point_step;
  msg.width = 2;
  msg.height = 1;
  msg.row_step = 2 * point_step;
  msg.data.assign(msg.row_step, 0);
  return msg;
}

trajectory_msgs::MultiDOFJointTrajectory onePoint(double qw, double qz) {
  trajectory_msgs::MultiDOFJointTrajectory msg;
  trajectory_msgs::MultiDOFJointTrajectoryPoint p;
  geometry_msgs::Transform tf;
  tf.rotation.w = qw;
  tf.rotation.z = qz;
  p.transforms.push_back(tf);
  msg.points.push_back(p);
  return msg;
}

}  // namespace

// libFuzzer (fuzz_depth_conversions, a timeout): width 0 and height ~4e9 made
// fromPointCloud2Msg walk 4e9 empty rows, stalling the mapper for seconds.
TEST(FuzzRegressions, EmptyCloudWithHugeHeightReturnsAtOnce) {
  sensor_msgs::PointCloud2 msg = xyzCloud(0, 4, 8, 16);
  msg.width = 0;
  msg.height = 0xfffffff0u;
  msg.row_step = 0;
  msg.data.clear();
  std::vector<Eigen::Vector3f> points(3);
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_TRUE(fromPointCloud2Msg(msg, &points).ok());
  EXPECT_TRUE(points.empty());
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0.5);
}

// Message fuzz test (PointClouds): x, y and z at overlapping offsets were read
// as three views of the same bytes; such a cloud is refused now.
TEST(FuzzRegressions, OverlappingXyzFieldsAreRefused) {
  std::vector<Eigen::Vector3f> points;
  const Status overlap = fromPointCloud2Msg(xyzCloud(0, 2, 8, 12), &points);
  EXPECT_FALSE(overlap.ok());
  EXPECT_NE(overlap.message().find("overlap"), std::string::npos) << overlap.message();
  EXPECT_FALSE(fromPointCloud2Msg(xyzCloud(0, 0, 0, 4), &points).ok());
  EXPECT_TRUE(fromPointCloud2Msg(xyzCloud(8, 4, 0, 12), &points).ok());  // any order, adjacent
  EXPECT_EQ(points.size(), 2u);
}

// Seen while writing the cloud oracle: field offsets of 2^31 or more were
// cast to a negative int and reported as
// a missing field. They are offsets beyond point_step.
TEST(FuzzRegressions, HugeFieldOffsetIsNamedAsSuch) {
  std::vector<Eigen::Vector3f> points;
  const Status s = fromPointCloud2Msg(xyzCloud(0x80000000u, 4, 8, 12), &points);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("point_step"), std::string::npos) << s.message();
}

// Message fuzz test (Trajectories): the yaw was read from any quaternion, so
// an unset (all-zero) rotation meant yaw 0 and a scaled one a wrong yaw.
TEST(FuzzRegressions, TrajectoryRotationsMustBeUnitQuaternions) {
  Trajectory trajectory;
  EXPECT_FALSE(fromTrajectoryMsg(onePoint(0.0, 0.0), 0.0, &trajectory).ok());
  EXPECT_FALSE(fromTrajectoryMsg(onePoint(2.0, 2.0), 0.0, &trajectory).ok());
  EXPECT_FALSE(fromTrajectoryMsg(onePoint(std::nan(""), 0.0), 0.0, &trajectory).ok());
  const double half = 0.5 * M_PI / 2;
  ASSERT_TRUE(fromTrajectoryMsg(onePoint(std::cos(half), std::sin(half)), 0.0, &trajectory).ok());
  EXPECT_NEAR(trajectory.points()[0].yaw, M_PI / 2, 1e-12);
}

// The CameraInfo checks, moved out of TsdfMapperServer::onCameraInfo into
// fromCameraInfoMsg for the fuzz tests: a focal length so small that the
// field of view rounds to 180 degrees, or a principal point far outside the
// image, gave rays of infinite or absurd size.
TEST(FuzzRegressions, CameraInfoWithDegenerateIntrinsicsIsRefused) {
  CameraConfig base;
  DepthCamera camera(base);
  sensor_msgs::CameraInfo msg;
  msg.width = 64;
  msg.height = 48;
  msg.K = {50.0, 0.0, 31.5, 0.0, 50.0, 23.5, 0.0, 0.0, 1.0};
  ASSERT_TRUE(fromCameraInfoMsg(msg, base, &camera).ok());
  EXPECT_EQ(camera.width(), 64);
  EXPECT_EQ(camera.cx(), 31.5);
  sensor_msgs::CameraInfo bad = msg;
  bad.K[0] = 1e-300;
  EXPECT_FALSE(fromCameraInfoMsg(bad, base, &camera).ok());
  bad = msg;
  bad.K[2] = 1e300;
  EXPECT_FALSE(fromCameraInfoMsg(bad, base, &camera).ok());
  bad = msg;
  bad.K[5] = -49.0;
  EXPECT_FALSE(fromCameraInfoMsg(bad, base, &camera).ok());
  EXPECT_EQ(camera.cx(), 31.5) << "a refused camera_info changed the camera";
}
