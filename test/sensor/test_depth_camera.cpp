#include "surface_nbv/sensor/depth_camera.h"

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace surface_nbv {
namespace {

using Eigen::Vector3d;

constexpr double kDeg = M_PI / 180.0;

// The default camera: 640 x 480, 90 x 60 deg, range [1.6, 8] m.
DepthCamera defaultCamera() { return DepthCamera(CameraConfig()); }

TEST(DepthCamera, DefaultConfigIsValid) {
  const CameraConfig config;
  EXPECT_EQ(config.width, 640);
  EXPECT_EQ(config.height, 480);
  EXPECT_DOUBLE_EQ(config.hfov_deg, 90.0);
  EXPECT_DOUBLE_EQ(config.vfov_deg, 60.0);
  EXPECT_DOUBLE_EQ(config.min_range, 1.6);
  EXPECT_DOUBLE_EQ(config.max_range, 8.0);
  const Status s = config.validate();
  EXPECT_TRUE(s.ok()) << s.message();
}

TEST(DepthCamera, IntrinsicsOf640x480At90x60Degrees) {
  const DepthCamera cam = defaultCamera();
  EXPECT_EQ(cam.width(), 640);
  EXPECT_EQ(cam.height(), 480);
  EXPECT_NEAR(cam.fx(), 320.0, 1e-9);
  EXPECT_NEAR(cam.fy(), 240.0 / std::tan(30.0 * kDeg), 1e-9);
  EXPECT_NEAR(cam.fy(), 415.69219381653056, 1e-9);
  EXPECT_DOUBLE_EQ(cam.cx(), 319.5);
  EXPECT_DOUBLE_EQ(cam.cy(), 239.5);
}

TEST(DepthCamera, IntrinsicsOfOddSizedImage) {
  CameraConfig config;
  config.width = 641;
  config.height = 481;
  config.hfov_deg = 60.0;
  config.vfov_deg = 45.0;
  const DepthCamera cam(config);
  EXPECT_DOUBLE_EQ(cam.cx(), 320.0);
  EXPECT_DOUBLE_EQ(cam.cy(), 240.0);
  EXPECT_NEAR(cam.fx(), 320.5 / std::tan(30.0 * kDeg), 1e-9);
  EXPECT_NEAR(cam.fy(), 240.5 / std::tan(22.5 * kDeg), 1e-9);
}

TEST(DepthCamera, PixelRayOfPrincipalPointIsOpticalAxis) {
  const DepthCamera cam = defaultCamera();
  const Vector3d r = cam.pixelRay(cam.cx(), cam.cy());
  EXPECT_DOUBLE_EQ(r.x(), 0.0);
  EXPECT_DOUBLE_EQ(r.y(), 0.0);
  EXPECT_DOUBLE_EQ(r.z(), 1.0);
}

TEST(DepthCamera, PixelRayHasUnitDepthAndOpticalFrameAxes) {
  const DepthCamera cam = defaultCamera();
  // Top-left pixel: left (x < 0) and up (y < 0); bottom-right: right and down.
  const Vector3d tl = cam.pixelRay(0, 0);
  EXPECT_DOUBLE_EQ(tl.z(), 1.0);
  EXPECT_NEAR(tl.x(), -319.5 / 320.0, 1e-12);
  EXPECT_NEAR(tl.y(), -239.5 / cam.fy(), 1e-12);
  const Vector3d br = cam.pixelRay(639, 479);
  EXPECT_DOUBLE_EQ(br.z(), 1.0);
  EXPECT_NEAR(br.x(), 319.5 / 320.0, 1e-12);
  EXPECT_NEAR(br.y(), 239.5 / cam.fy(), 1e-12);
  // The outer pixel edges lie on the FOV: x / z = tan(45 deg), y / z = tan(30 deg).
  EXPECT_NEAR(cam.pixelRay(-0.5, 0).x(), -1.0, 1e-12);
  EXPECT_NEAR(cam.pixelRay(639.5, 0).x(), 1.0, 1e-12);
  EXPECT_NEAR(cam.pixelRay(0, -0.5).y(), -std::tan(30.0 * kDeg), 1e-12);
  EXPECT_NEAR(cam.pixelRay(0, 479.5).y(), std::tan(30.0 * kDeg), 1e-12);
}

TEST(DepthCamera, ProjectInvertsPixelRay) {
  const DepthCamera cam = defaultCamera();
  int checked = 0;
  for (double col : {0.0, 0.25, 17.0, 319.5, 320.0, 511.75, 639.0}) {
    for (double row : {0.0, 100.5, 239.5, 300.0, 479.0}) {
      for (double z : {0.5, 1.6, 3.25, 8.0, 40.0}) {
        const Vector3d p = z * cam.pixelRay(col, row);
        EXPECT_DOUBLE_EQ(p.z(), z);
        double u = -1.0, v = -1.0;
        ASSERT_TRUE(cam.project(p, &u, &v)) << col << " " << row << " " << z;
        EXPECT_NEAR(u, col, 1e-9);
        EXPECT_NEAR(v, row, 1e-9);
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 7 * 5 * 5);
}

TEST(DepthCamera, ProjectIsPinholeModel) {
  const DepthCamera cam = defaultCamera();
  double u = 0.0, v = 0.0;
  ASSERT_TRUE(cam.project(Vector3d(1.0, -0.5, 4.0), &u, &v));
  EXPECT_NEAR(u, 320.0 * 0.25 + 319.5, 1e-9);
  EXPECT_NEAR(v, cam.fy() * -0.125 + 239.5, 1e-9);
}

TEST(DepthCamera, ProjectRejectsPointsBehindOrOnTheCameraPlane) {
  const DepthCamera cam = defaultCamera();
  double u = 7.0, v = 9.0;
  EXPECT_FALSE(cam.project(Vector3d(0.0, 0.0, -3.0), &u, &v));
  EXPECT_FALSE(cam.project(Vector3d(0.1, 0.1, 0.0), &u, &v));
  EXPECT_FALSE(cam.project(Vector3d(0.0, 0.0, std::numeric_limits<double>::quiet_NaN()), &u, &v));
  // Outputs are untouched on failure.
  EXPECT_EQ(u, 7.0);
  EXPECT_EQ(v, 9.0);
}

// A point at angle `a` off the optical axis towards +x (horizontal) or +y
// (vertical), at range r.
Vector3d atAngle(double a, bool horizontal, double r = 4.0) {
  return horizontal ? Vector3d(r * std::sin(a), 0.0, r * std::cos(a)) : Vector3d(0.0, r * std::sin(a), r * std::cos(a));
}

TEST(DepthCamera, HorizontalFovEdges) {
  const DepthCamera cam = defaultCamera();
  const double half = 45.0 * kDeg;
  const double eps = 1e-6;
  double u = 0.0, v = 0.0;
  for (double sign : {-1.0, 1.0}) {
    Vector3d inside = atAngle(sign * (half - eps), true);
    ASSERT_TRUE(cam.project(inside, &u, &v)) << sign;
    EXPECT_NEAR(u, sign > 0 ? 639.5 : -0.5, 1e-3);
    EXPECT_NEAR(v, 239.5, 1e-9);
    EXPECT_TRUE(cam.sees(inside));
    Vector3d outside = atAngle(sign * (half + eps), true);
    EXPECT_FALSE(cam.project(outside, &u, &v)) << sign;
    EXPECT_FALSE(cam.sees(outside));
  }
}

TEST(DepthCamera, VerticalFovEdges) {
  const DepthCamera cam = defaultCamera();
  const double half = 30.0 * kDeg;
  const double eps = 1e-6;
  double u = 0.0, v = 0.0;
  for (double sign : {-1.0, 1.0}) {
    Vector3d inside = atAngle(sign * (half - eps), false);
    ASSERT_TRUE(cam.project(inside, &u, &v)) << sign;
    EXPECT_NEAR(v, sign > 0 ? 479.5 : -0.5, 1e-3);
    EXPECT_NEAR(u, 319.5, 1e-9);
    EXPECT_TRUE(cam.sees(inside));
    EXPECT_FALSE(cam.project(atAngle(sign * (half + eps), false), &u, &v)) << sign;
    EXPECT_FALSE(cam.sees(atAngle(sign * (half + eps), false)));
  }
  // 40 deg is inside the horizontal FOV but outside the vertical one.
  EXPECT_TRUE(cam.sees(atAngle(40.0 * kDeg, true)));
  EXPECT_FALSE(cam.sees(atAngle(40.0 * kDeg, false)));
}

TEST(DepthCamera, SeesRespectsDepthRangeOnZ) {
  const DepthCamera cam = defaultCamera();
  EXPECT_FALSE(cam.sees(Vector3d(0, 0, 1.0)));
  EXPECT_FALSE(cam.sees(Vector3d(0, 0, 1.599)));
  EXPECT_TRUE(cam.sees(Vector3d(0, 0, 1.6)));
  EXPECT_TRUE(cam.sees(Vector3d(0, 0, 5.0)));
  EXPECT_TRUE(cam.sees(Vector3d(0, 0, 8.0)));
  EXPECT_FALSE(cam.sees(Vector3d(0, 0, 8.001)));
  EXPECT_FALSE(cam.sees(Vector3d(0, 0, 100.0)));
  // The range is on z, not on the Euclidean distance: this point is 8.9 m
  // away but at z = 7.9.
  const Vector3d oblique(4.1, 0.0, 7.9);
  ASSERT_GT(oblique.norm(), 8.0);
  EXPECT_TRUE(cam.sees(oblique));
  // In range but outside the image.
  EXPECT_FALSE(cam.sees(Vector3d(6.0, 0.0, 5.0)));

  EXPECT_FALSE(cam.depthInRange(1.5999));
  EXPECT_TRUE(cam.depthInRange(1.6));
  EXPECT_TRUE(cam.depthInRange(8.0));
  EXPECT_FALSE(cam.depthInRange(8.0001));
  EXPECT_FALSE(cam.depthInRange(std::numeric_limits<double>::quiet_NaN()));
}

TEST(DepthCamera, CustomRangeIsUsed) {
  CameraConfig config;
  config.min_range = 0.0;
  config.max_range = 2.0;
  const DepthCamera cam(config);
  EXPECT_TRUE(cam.sees(Vector3d(0, 0, 0.01)));
  EXPECT_TRUE(cam.sees(Vector3d(0, 0, 2.0)));
  EXPECT_FALSE(cam.sees(Vector3d(0, 0, 2.01)));
}

// validate() must fail and name `key` in its message.
void expectRejected(const CameraConfig& config, const std::string& key) {
  const Status s = config.validate();
  EXPECT_FALSE(s.ok()) << key;
  EXPECT_NE(s.message().find(key), std::string::npos) << "message '" << s.message() << "' lacks " << key;
}

TEST(DepthCamera, ValidateRejectsEachBadField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  // One bad field per row, the rest at their defaults.
  struct Bad {
    const char* key;
    std::function<void(CameraConfig*)> set;
  };
  const std::vector<Bad> rows = {
      {"camera/width", [](CameraConfig* c) { c->width = 0; }},
      {"camera/width", [](CameraConfig* c) { c->width = -640; }},
      {"camera/height", [](CameraConfig* c) { c->height = 0; }},
      {"camera/hfov_deg", [](CameraConfig* c) { c->hfov_deg = 180.0; }},
      {"camera/hfov_deg", [](CameraConfig* c) { c->hfov_deg = 0.0; }},
      {"camera/hfov_deg", [&](CameraConfig* c) { c->hfov_deg = nan; }},
      {"camera/vfov_deg", [&](CameraConfig* c) { c->vfov_deg = nan; }},
      {"camera/vfov_deg", [](CameraConfig* c) { c->vfov_deg = 200.0; }},
      {"camera/min_range", [](CameraConfig* c) { c->min_range = -0.1; }},
      {"camera/min_range", [&](CameraConfig* c) { c->min_range = nan; }},
      {"camera/max_range", [](CameraConfig* c) { c->max_range = c->min_range; }},
      {"camera/max_range", [](CameraConfig* c) { c->max_range = 1.0; }},
      {"camera/max_range", [&](CameraConfig* c) { c->max_range = inf; }},
      {"camera/rate_hz", [](CameraConfig* c) { c->rate_hz = 0.0; }},
      {"camera/rate_hz", [](CameraConfig* c) { c->rate_hz = -30.0; }},
      {"camera/noise_k", [](CameraConfig* c) { c->noise_k = -0.01; }},
      {"camera/noise_k", [&](CameraConfig* c) { c->noise_k = nan; }},
      // The 60 degree FOV's edge would pass the vertical.
      {"camera/pitch_deg", [](CameraConfig* c) { c->pitch_deg = 60.0; }},
      {"camera/pitch_deg", [](CameraConfig* c) { c->pitch_deg = -60.0; }},
      {"camera/pitch_deg", [&](CameraConfig* c) { c->pitch_deg = nan; }},
  };
  for (const Bad& row : rows) {
    CameraConfig c;
    row.set(&c);
    expectRejected(c, row.key);
  }
  CameraConfig steep;
  steep.pitch_deg = 59.9;
  EXPECT_TRUE(steep.validate());
}

// A pose may sit up to vfov / 2 + pitch above a point it sees and
// vfov / 2 - pitch below it, less the margin.
TEST(DepthCamera, PoseElevationWindowFollowsThePitch) {
  CameraConfig c;  // 60 degrees vertical
  EXPECT_DOUBLE_EQ(c.minPoseElevationDeg(), -30.0);
  EXPECT_DOUBLE_EQ(c.maxPoseElevationDeg(), 30.0);
  c.pitch_deg = 10.0;
  EXPECT_DOUBLE_EQ(c.minPoseElevationDeg(), -20.0);
  EXPECT_DOUBLE_EQ(c.maxPoseElevationDeg(), 40.0);
  EXPECT_DOUBLE_EQ(c.minPoseElevationDeg(2.0), -18.0);
  EXPECT_DOUBLE_EQ(c.maxPoseElevationDeg(2.0), 38.0);
}

TEST(DepthCamera, ValidateAcceptsBoundaryValues) {
  CameraConfig c;
  c.width = 1;
  c.height = 1;
  c.hfov_deg = 179.0;
  c.vfov_deg = 0.5;
  c.min_range = 0.0;
  c.max_range = 1e-3;
  c.rate_hz = 1000.0;
  c.noise_k = 0.0;
  const Status s = c.validate();
  EXPECT_TRUE(s.ok()) << s.message();
}

TEST(DepthCamera, ValidateMessageCarriesTheBadValue) {
  CameraConfig c;
  c.hfov_deg = 180.0;
  const Status s = c.validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("180"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace surface_nbv
