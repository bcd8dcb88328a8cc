// The depth sensor model (sensor_model.h) through the renderer: ToF-like
// noise, lateral edge noise, dropouts, quantisation, and that every draw is a
// pure function of (seed, frame, pixel).
#include "render_test_helpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "surface_nbv/sensor/sensor_model.h"

namespace surface_nbv {
namespace {

using Eigen::Vector3d;
using namespace render_test;

// A wall at z = 6 and a box face at z = 3 in front of it, seen head on.
TriangleMesh wallAndBox() {
  TriangleMesh mesh = planeAtZ(6.0);
  addQuad(&mesh, Vector3d(0, 0, 3.0), Vector3d(1.0, 0, 0), Vector3d(0, 1.0, 0));
  return mesh;
}

// Every effect of the model at once.
CameraConfig realCamera(uint64_t seed) {
  CameraConfig c;
  c.noise_k = 0.007;
  c.noise_seed = seed;
  c.sensor.noise_sigma0 = 0.005;
  c.sensor.noise_sigma1 = 0.002;
  c.sensor.lateral_noise_px = 0.7;
  c.sensor.grazing_dropout_deg = 70.0;
  c.sensor.dropout_rate = 0.02;
  c.sensor.dropout_patch_fraction = 0.2;
  c.sensor.dropout_patch_size = 0.5;
  c.sensor.dropout_patch_rate = 0.8;
  c.sensor.quantization = 0.001;
  return c;
}

size_t differing(const DepthImage& a, const DepthImage& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    const float x = a.data[i], y = b.data[i];
    n += (x == y || (std::isnan(x) && std::isnan(y))) ? 0 : 1;
  }
  return n;
}

size_t countNaN(const DepthImage& image) {
  size_t n = 0;
  for (float z : image.data) n += std::isnan(z) ? 1 : 0;
  return n;
}

TEST(SensorModel, SeededImagesAreDeterministicWhateverTheThreadCount) {
  const auto scene = buildScene(wallAndBox());
  ASSERT_NE(scene, nullptr);
  const Transform T = lookAlong(Vector3d(0.3, -0.2, 0.0), Vector3d(0.2, 0.1, 1.0), Vector3d::UnitY());
  CameraConfig c = realCamera(11);
  ASSERT_TRUE(c.validate().ok()) << c.validate().message();
  const DepthImage one = render(*scene, c, T, 1, 5);
  EXPECT_EQ(differing(one, render(*scene, c, T, 2, 5)), 0u);
  EXPECT_EQ(differing(one, render(*scene, c, T, 3, 5)), 0u);
  EXPECT_EQ(differing(one, render(*scene, c, T, 1, 5)), 0u);
  // Every effect is there: invalid pixels, and noisy depths on the wall.
  EXPECT_GT(countNaN(one), one.data.size() / 100);
  EXPECT_GT(one.validCount(), one.data.size() / 2);
  // Another frame or seed draws again.
  EXPECT_GT(differing(one, render(*scene, c, T, 2, 6)), one.data.size() / 2);
  c.noise_seed = 12;
  EXPECT_GT(differing(one, render(*scene, c, T, 2, 5)), one.data.size() / 2);
}

TEST(SensorModel, TheDefaultCameraIsPerfect) {
  const CameraConfig c;
  EXPECT_FALSE(c.sensor.enabled());
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  const DepthImage image = render(*scene, c, Transform::Identity(), 2);
  EXPECT_EQ(image.validCount(), image.data.size());
  for (float z : image.data) ASSERT_NEAR(z, 5.0f, 1e-5f);
}

TEST(SensorModel, TofNoiseHasSigmaConstantPlusLinear) {
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  CameraConfig c;
  c.sensor.noise_sigma0 = 0.01;
  c.sensor.noise_sigma1 = 0.005;
  const double sigma = 0.01 + 0.005 * 5.0;
  EXPECT_DOUBLE_EQ(axialSigma(c.sensor, 0.0, 5.0), sigma);
  const DepthImage image = render(*scene, c, Transform::Identity(), 2, 3);
  double sum = 0.0, sum2 = 0.0;
  size_t n = 0;
  for (float z : image.data) {
    ASSERT_TRUE(std::isfinite(z));
    sum += z - 5.0;
    sum2 += (z - 5.0) * (z - 5.0);
    ++n;
  }
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(sd, sigma, 0.01 * sigma);
  EXPECT_NEAR(mean, 0.0, 4.0 * sigma / std::sqrt(static_cast<double>(n)));
}

TEST(SensorModel, StereoNoiseAloneIsTheRenderersNoisyDepth) {
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  CameraConfig c;
  c.noise_k = 0.01;
  c.noise_seed = 3;
  c.sensor.quantization = 1e-9;  // switches the whole model on, rounds nothing that float keeps
  ASSERT_TRUE(c.sensor.enabled());
  const DepthImage image = render(*scene, c, Transform::Identity(), 2, 4);
  for (int row : {0, 100, 479}) {
    for (int col : {0, 320, 639}) {
      EXPECT_NEAR(image.at(row, col), noisyDepth(5.0f, 0.01, 3, 4, static_cast<uint64_t>(row) * 640 + col), 1e-5);
    }
  }
}

TEST(SensorModel, QuantisesToMillimetres) {
  const TiltedPlane plane;
  const auto scene = buildScene(plane.mesh(Transform::Identity()));
  ASSERT_NE(scene, nullptr);
  CameraConfig c;
  c.sensor.quantization = 0.001;
  const DepthImage image = render(*scene, c, Transform::Identity(), 2);
  const DepthCamera cam(c);
  size_t n = 0;
  for (int row = 0; row < cam.height(); row += 7) {
    for (int col = 0; col < cam.width(); col += 7) {
      const float z = image.at(row, col);
      if (!std::isfinite(z)) continue;
      ++n;
      const double mm = static_cast<double>(z) * 1000.0;
      ASSERT_NEAR(mm, std::round(mm), 1e-3) << z;
      ASSERT_NEAR(z, plane.depth(cam, col, row), 0.0005 + 1e-5);
    }
  }
  EXPECT_GT(n, 4000u);
}

TEST(SensorModel, RandomDropoutsAreInvalidNotFreeSpace) {
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  CameraConfig c;
  c.sensor.dropout_rate = 0.1;
  const DepthImage image = render(*scene, c, Transform::Identity(), 2);
  size_t nan = 0;
  for (float z : image.data) {
    nan += std::isnan(z) ? 1 : 0;
    ASSERT_FALSE(std::isinf(z));  // never +Inf: that would clear the space in front of the plane
  }
  // Binomial: sd = sqrt(0.1 * 0.9 / 307200) = 0.054 %.
  EXPECT_NEAR(static_cast<double>(nan) / image.data.size(), 0.1, 0.003);
}

TEST(SensorModel, GrazingAnglesDropOutPastTheThreshold) {
  // The ground z = 0 seen from 1.5 m up, looking level: incidence grows
  // towards the horizon.
  const auto scene = buildScene(planeAtZ(0.0, 200.0));
  ASSERT_NE(scene, nullptr);
  CameraConfig c;
  c.max_range = 30.0;
  c.sensor.grazing_dropout_deg = 75.0;
  const Transform T = lookAlong(Vector3d(0, 0, 1.5), Vector3d(1, 0, -0.3));
  const DepthCamera cam(c);
  const DepthImage image = render(*scene, c, T, 2);
  size_t below = 0, steep = 0, steep_dropped = 0;
  for (int row = 0; row < cam.height(); ++row) {
    for (int col = 0; col < cam.width(); ++col) {
      const Vector3d d = T.linear() * cam.pixelRay(col, row);
      if (!(d.z() < 0.0)) continue;  // sky
      const double incidence = std::acos(std::abs(d.normalized().z())) * 180.0 / M_PI;
      const float z = image.at(row, col);
      if (incidence < 74.0) {
        ++below;
        const double t = -1.5 / d.z();  // the true depth
        if (t >= c.min_range && t <= c.max_range) {
          ASSERT_FALSE(std::isnan(z)) << incidence;
        }
      } else if (incidence > 85.0 && -1.5 / d.z() < 28.0) {  // hit within max range
        ++steep;
        steep_dropped += std::isnan(z) ? 1 : 0;
      }
    }
  }
  ASSERT_GT(below, 10000u);
  ASSERT_GT(steep, 1000u);
  // Past 85 deg at least 2 / 3 drop (the ramp reaches 1 at 90 deg), within 28 m 0.74 on average.
  EXPECT_GT(static_cast<double>(steep_dropped) / steep, 0.62);
}

TEST(SensorModel, DarkPatchesStayOnTheSurfaceFromEveryView) {
  const auto scene = buildScene(planeAtZ(5.25));  // mid-cube in z
  ASSERT_NE(scene, nullptr);
  CameraConfig c;
  c.noise_seed = 21;
  c.sensor.dropout_patch_fraction = 0.3;
  c.sensor.dropout_patch_size = 0.5;
  c.sensor.dropout_patch_rate = 1.0;
  const DepthCamera cam(c);
  size_t in_patch = 0, outside = 0;
  uint64_t frame = 0;
  for (const Transform& T : {Transform(Transform::Identity()),
                             lookAlong(Vector3d(1.3, 0.4, 0.5), Vector3d(-0.2, 0.1, 1.0), Vector3d::UnitY())}) {
    const DepthImage image = render(*scene, c, T, 2, frame++);
    for (int row = 0; row < cam.height(); row += 3) {
      for (int col = 0; col < cam.width(); col += 3) {
        const Vector3d d = T.linear() * cam.pixelRay(col, row);
        const Vector3d p = T.translation() + d * ((5.25 - T.translation().z()) / d.z());
        // Away from the cubes' faces, where float rounding decides.
        const Vector3d f = p / 0.5 - (p / 0.5).array().floor().matrix();
        if ((f.head<2>().array() < 0.02).any() || (f.head<2>().array() > 0.98).any()) continue;
        const bool patch = inDropoutPatch(c.sensor, 21, p);
        (patch ? in_patch : outside) += 1;
        ASSERT_EQ(std::isnan(image.at(row, col)), patch) << p.transpose();
      }
    }
  }
  const double share = static_cast<double>(in_patch) / (in_patch + outside);
  EXPECT_GT(share, 0.15);
  EXPECT_LT(share, 0.45);
}

TEST(SensorModel, LateralNoiseFraysDepthEdgesOnly) {
  const auto scene = buildScene(wallAndBox());
  ASSERT_NE(scene, nullptr);
  CameraConfig clean;
  CameraConfig c;
  c.sensor.lateral_noise_px = 1.0;
  const DepthCamera cam(c);
  const DepthImage truth = render(*scene, clean, Transform::Identity(), 2);
  const DepthImage image = render(*scene, c, Transform::Identity(), 2, 1);
  // Flat regions keep their depth; pixels next to the box's edge take either side's.
  size_t edge_changed = 0, flat_changed = 0;
  // (An offset past 5 px has a probability of 4e-8.)
  for (int row = 5; row < cam.height() - 5; ++row) {
    for (int col = 5; col < cam.width() - 5; ++col) {
      bool near_edge = false;
      for (int dr = -5; dr <= 5; ++dr)
        for (int dc = -5; dc <= 5; ++dc) near_edge |= std::abs(truth.at(row + dr, col + dc) - truth.at(row, col)) > 1e-3f;
      const float z = image.at(row, col);
      ASSERT_TRUE(std::abs(z - 3.0f) < 1e-4f || std::abs(z - 6.0f) < 1e-4f) << z;
      const bool changed = std::abs(z - truth.at(row, col)) > 1e-3f;
      (near_edge ? edge_changed : flat_changed) += changed ? 1 : 0;
    }
  }
  EXPECT_EQ(flat_changed, 0u);
  EXPECT_GT(edge_changed, 100u);
}

TEST(SensorModel, BadFieldsAreNamed) {
  const std::vector<std::pair<std::string, std::function<void(SensorModelConfig*)>>> cases = {
      {"camera/noise_sigma0", [](SensorModelConfig* s) { s->noise_sigma0 = -0.1; }},
      {"camera/noise_sigma1", [](SensorModelConfig* s) { s->noise_sigma1 = std::nan(""); }},
      {"camera/lateral_noise_px", [](SensorModelConfig* s) { s->lateral_noise_px = -1.0; }},
      {"camera/grazing_dropout_deg", [](SensorModelConfig* s) { s->grazing_dropout_deg = 90.0; }},
      {"camera/dropout_rate", [](SensorModelConfig* s) { s->dropout_rate = 1.5; }},
      {"camera/dropout_patch_fraction", [](SensorModelConfig* s) { s->dropout_patch_fraction = -0.5; }},
      {"camera/dropout_patch_size", [](SensorModelConfig* s) { s->dropout_patch_size = 0.0; }},
      {"camera/dropout_patch_rate", [](SensorModelConfig* s) { s->dropout_patch_rate = 2.0; }},
      {"camera/quantization", [](SensorModelConfig* s) { s->quantization = -0.001; }},
  };
  for (const auto& [key, spoil] : cases) {
    CameraConfig c;
    spoil(&c.sensor);
    const Status s = c.validate();
    ASSERT_FALSE(s.ok()) << key;
    EXPECT_EQ(s.message().rfind(key, 0), 0u) << s.message();
  }
  EXPECT_TRUE(realCamera(1).validate().ok());
}

}  // namespace
}  // namespace surface_nbv
