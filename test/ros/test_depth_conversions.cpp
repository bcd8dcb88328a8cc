#include "surface_nbv/ros/depth_conversions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include <sensor_msgs/image_encodings.h>

using namespace surface_nbv;

namespace {

sensor_msgs::Image floatImage(const std::vector<float>& values, int w, int h) {
  DepthImage d;
  d.resize(w, h);
  d.data = values;
  sensor_msgs::Image msg;
  toImageMsg(d, std_msgs::Header(), &msg);
  return msg;
}

}  // namespace

TEST(DepthConversions, FloatRoundTripKeepsValuesAndMakesBadDepthNaN) {
  const float inf = std::numeric_limits<float>::infinity();
  const sensor_msgs::Image msg = floatImage({1.5f, NAN, 0.0f, -2.0f, inf, 7.25f, -inf, 3.0f}, 4, 2);
  EXPECT_EQ(msg.encoding, "32FC1");
  EXPECT_EQ(msg.step, 16u);
  DepthImage back;
  ASSERT_TRUE(fromImageMsg(msg, &back).ok());
  EXPECT_FLOAT_EQ(back.at(0, 0), 1.5f);
  EXPECT_TRUE(std::isnan(back.at(0, 1)));
  EXPECT_TRUE(std::isnan(back.at(0, 2)));  // zero = invalid
  EXPECT_TRUE(std::isnan(back.at(0, 3)));  // negative
  EXPECT_EQ(back.at(1, 0), inf);           // REP 117: no return within range
  EXPECT_FLOAT_EQ(back.at(1, 1), 7.25f);
  EXPECT_EQ(back.at(1, 2), -inf);          // REP 117: too close
  EXPECT_FLOAT_EQ(back.at(1, 3), 3.0f);
}

TEST(DepthConversions, MillimetreImagesAndPaddedRows) {
  sensor_msgs::Image msg;
  msg.encoding = "16UC1";
  msg.width = 2;
  msg.height = 2;
  msg.step = 6;  // 2 bytes of padding a row
  msg.data.assign(12, 0);
  const uint16_t mm[4] = {1600, 0, 8000, 65535};
  std::memcpy(&msg.data[0], &mm[0], 2);
  std::memcpy(&msg.data[2], &mm[1], 2);
  std::memcpy(&msg.data[6], &mm[2], 2);
  std::memcpy(&msg.data[8], &mm[3], 2);
  DepthImage d;
  ASSERT_TRUE(fromImageMsg(msg, &d).ok());
  EXPECT_FLOAT_EQ(d.at(0, 0), 1.6f);
  EXPECT_TRUE(std::isnan(d.at(0, 1)));
  EXPECT_FLOAT_EQ(d.at(1, 0), 8.0f);
  EXPECT_NEAR(d.at(1, 1), 65.535f, 1e-4);
}

// depth_sim's ~encoding 16UC1 (issue #40): millimetres, 0 for anything
// without a depth, read back as the mapper reads it.
TEST(DepthConversions, MillimetreOutputRoundsAndZeroesWhatHasNoDepth) {
  const float inf = std::numeric_limits<float>::infinity();
  DepthImage depth;
  depth.resize(6, 1);
  depth.data = {1.6004f, 4.2376f, NAN, inf, -inf, 70.0f};
  sensor_msgs::Image msg;
  toImageMsgMillimetres(depth, std_msgs::Header(), &msg);
  EXPECT_EQ(msg.encoding, "16UC1");
  EXPECT_EQ(msg.step, 12u);
  DepthImage back;
  ASSERT_TRUE(fromImageMsg(msg, &back).ok());
  EXPECT_FLOAT_EQ(back.at(0, 0), 1.6f);
  EXPECT_FLOAT_EQ(back.at(0, 1), 4.238f);
  for (int col = 2; col < 6; ++col) EXPECT_TRUE(std::isnan(back.at(0, col))) << col;  // 0: invalid
}

TEST(DepthConversions, BigEndianFloat) {
  sensor_msgs::Image msg = floatImage({2.0f}, 1, 1);
  std::reverse(msg.data.begin(), msg.data.end());
  msg.is_bigendian = 1;
  DepthImage d;
  ASSERT_TRUE(fromImageMsg(msg, &d).ok());
  EXPECT_FLOAT_EQ(d.at(0, 0), 2.0f);
}

TEST(DepthConversions, RejectsMalformedImages) {
  DepthImage d;
  d.resize(1, 1);
  sensor_msgs::Image msg = floatImage({1, 2, 3, 4}, 2, 2);
  sensor_msgs::Image bad = msg;
  bad.encoding = "rgb8";
  Status s = fromImageMsg(bad, &d);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("rgb8"), std::string::npos);
  bad = msg;
  bad.step = 4;
  EXPECT_FALSE(fromImageMsg(bad, &d).ok());
  bad = msg;
  bad.data.resize(15);
  EXPECT_NE(fromImageMsg(bad, &d).message().find("bytes"), std::string::npos);
  bad = msg;
  bad.width = 0;
  EXPECT_FALSE(fromImageMsg(bad, &d).ok());
  bad = msg;
  bad.height = 100000;
  EXPECT_FALSE(fromImageMsg(bad, &d).ok());
  EXPECT_EQ(d.width, 1);  // untouched by every refusal
}

TEST(DepthConversions, CameraInfoMatchesModel) {
  CameraConfig c;
  const DepthCamera cam(c);
  sensor_msgs::CameraInfo info;
  std_msgs::Header h;
  h.frame_id = "camera";
  toCameraInfoMsg(cam, h, &info);
  EXPECT_EQ(info.width, 640u);
  EXPECT_EQ(info.height, 480u);
  EXPECT_DOUBLE_EQ(info.K[0], 320.0);
  EXPECT_NEAR(info.K[4], 240.0 / std::tan(M_PI / 6), 1e-9);
  EXPECT_DOUBLE_EQ(info.K[2], 319.5);
  EXPECT_DOUBLE_EQ(info.K[5], 239.5);
  EXPECT_DOUBLE_EQ(info.P[0], info.K[0]);
  EXPECT_DOUBLE_EQ(info.P[10], 1.0);
  EXPECT_EQ(info.header.frame_id, "camera");
  EXPECT_EQ(info.D.size(), 5u);
}

TEST(DepthConversions, PointCloudLayout) {
  sensor_msgs::PointCloud2 cloud;
  toPointCloud2Msg({Eigen::Vector3f(1, 2, 3), Eigen::Vector3f(-1, 0, 5)}, std_msgs::Header(), &cloud);
  ASSERT_EQ(cloud.width, 2u);
  ASSERT_EQ(cloud.fields.size(), 3u);
  EXPECT_EQ(cloud.fields[2].name, "z");
  EXPECT_EQ(cloud.fields[2].offset, 8u);
  float z;
  std::memcpy(&z, &cloud.data[12 + 8], 4);
  EXPECT_FLOAT_EQ(z, 5.0f);
}

TEST(DepthConversions, TransformValidation) {
  geometry_msgs::Transform t;
  t.rotation.w = 1.0;
  t.translation.x = 2.0;
  Transform T;
  ASSERT_TRUE(fromTransformMsg(t, &T).ok());
  EXPECT_DOUBLE_EQ(T.translation().x(), 2.0);
  geometry_msgs::Transform bad = t;
  bad.translation.y = NAN;
  EXPECT_FALSE(fromTransformMsg(bad, &T).ok());
  bad = t;
  bad.rotation.w = 0.0;  // zero quaternion
  EXPECT_FALSE(fromTransformMsg(bad, &T).ok());
  bad = t;
  bad.rotation.x = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(fromTransformMsg(bad, &T).ok());
}

TEST(DepthConversions, MeshMarkerHasThreePointsPerTriangle) {
  TriangleMesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.triangles = {{0, 1, 2}, {0, 1, 3}};
  visualization_msgs::Marker m;
  std_msgs::Header h;
  h.frame_id = "world";
  toMeshMarker(mesh, h, "gt", &m);
  EXPECT_EQ(m.type, visualization_msgs::Marker::TRIANGLE_LIST);
  ASSERT_EQ(m.points.size(), 6u);
  EXPECT_DOUBLE_EQ(m.points[5].z, 1.0);
  EXPECT_DOUBLE_EQ(m.pose.orientation.w, 1.0);
}

TEST(DepthConversions, PointCloudRoundTripAndPaddedLayouts) {
  sensor_msgs::PointCloud2 cloud;
  toPointCloud2Msg({Eigen::Vector3f(1, 2, 3), Eigen::Vector3f(NAN, 0, 5)}, std_msgs::Header(), &cloud);
  std::vector<Eigen::Vector3f> back;
  ASSERT_TRUE(fromPointCloud2Msg(cloud, &back).ok());
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0], Eigen::Vector3f(1, 2, 3));
  EXPECT_TRUE(std::isnan(back[1].x()));  // kept: the integrator counts it as invalid
  // A padded layout (x, y, z, intensity in 16 bytes) with fields out of order.
  sensor_msgs::PointCloud2 padded = cloud;
  padded.point_step = 16;
  padded.row_step = 32;
  padded.fields[0].offset = 8;  // x after y and z
  padded.fields[1].offset = 0;
  padded.fields[2].offset = 4;
  padded.data.assign(32, 0);
  const float v[3] = {7, 8, 9};  // y, z, x
  std::memcpy(&padded.data[16], v, 12);
  ASSERT_TRUE(fromPointCloud2Msg(padded, &back).ok());
  EXPECT_EQ(back[1], Eigen::Vector3f(9, 7, 8));
}

TEST(DepthConversions, RejectsMalformedClouds) {
  sensor_msgs::PointCloud2 cloud;
  toPointCloud2Msg({Eigen::Vector3f(1, 2, 3)}, std_msgs::Header(), &cloud);
  std::vector<Eigen::Vector3f> out;
  auto refuse = [&](sensor_msgs::PointCloud2 bad, const std::string& what) {
    const Status s = fromPointCloud2Msg(bad, &out);
    EXPECT_FALSE(s.ok()) << what;
    EXPECT_NE(s.message().find(what), std::string::npos) << s.message();
  };
  sensor_msgs::PointCloud2 bad = cloud;
  bad.fields.pop_back();
  refuse(bad, "no field z");
  bad = cloud;
  bad.fields[0].datatype = sensor_msgs::PointField::FLOAT64;
  refuse(bad, "float32");
  bad = cloud;
  bad.data.resize(11);
  refuse(bad, "bytes");
  bad = cloud;
  bad.width = 100000000;
  refuse(bad, "out of range");
  bad = cloud;
  bad.fields[2].offset = 10;
  refuse(bad, "point_step");
  bad = cloud;
  bad.is_bigendian = true;
  refuse(bad, "big-endian");
}
