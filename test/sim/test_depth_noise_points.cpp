// Depth noise, back-projection and procedural scenes through the renderer.
#include "render_test_helpers.h"

#include <gtest/gtest.h>

#include <limits>

namespace surface_nbv {
namespace {

using Eigen::Vector3d;
using namespace render_test;

// ---- (g) noise ----

struct Stats {
  double mean = 0.0, stddev = 0.0, within_one_sigma = 0.0;
  size_t n = 0;
};

Stats noiseStats(const DepthImage& image, double truth, double sigma) {
  Stats s;
  double sum = 0.0, sum2 = 0.0;
  size_t within = 0;
  for (float z : image.data) {
    if (!std::isfinite(z)) continue;
    const double e = z - truth;
    sum += e;
    sum2 += e * e;
    within += std::abs(e) <= sigma ? 1 : 0;
    ++s.n;
  }
  s.mean = sum / s.n;
  s.stddev = std::sqrt(sum2 / s.n - s.mean * s.mean);
  s.within_one_sigma = static_cast<double>(within) / s.n;
  return s;
}

TEST(DepthRenderer, NoiseHasSigmaKZSquared) {
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  CameraConfig config;
  config.noise_k = 0.01;
  config.noise_seed = 7;
  const DepthImage image = render(*scene, config, Transform::Identity(), 2, 3);
  const double sigma = 0.01 * 5.0 * 5.0;
  const Stats s = noiseStats(image, 5.0, sigma);
  ASSERT_EQ(s.n, 640u * 480u);  // 5 +- 12 sigma stays inside [1.6, 8]
  EXPECT_NEAR(s.stddev, sigma, 0.05 * sigma);
  EXPECT_NEAR(s.stddev, sigma, 0.01 * sigma);
  EXPECT_NEAR(s.mean, 0.0, 4.0 * sigma / std::sqrt(static_cast<double>(s.n)));
  // Gaussian: 68.27 % within one sigma (binomial sd 0.08 %).
  EXPECT_NEAR(s.within_one_sigma, 0.6827, 0.005);
}

TEST(DepthRenderer, NoiseIsAPureFunctionOfSeedFrameAndPixel) {
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  CameraConfig config;
  config.noise_k = 0.01;
  config.noise_seed = 42;
  const DepthImage one = render(*scene, config, Transform::Identity(), 1, 9);
  const DepthImage two = render(*scene, config, Transform::Identity(), 2, 9);
  const DepthImage three = render(*scene, config, Transform::Identity(), 3, 9);
  ASSERT_EQ(one.data.size(), two.data.size());
  EXPECT_TRUE(one.data == two.data);
  EXPECT_TRUE(one.data == three.data);
  EXPECT_TRUE(one.data == render(*scene, config, Transform::Identity(), 1, 9).data);
  // Pixel (row, col) is keyed by row * width + col.
  for (int row : {0, 17, 240, 479}) {
    for (int col : {0, 5, 319, 639}) {
      const float expected = noisyDepth(5.0f, 0.01, 42, 9, static_cast<uint64_t>(row) * 640 + col);
      EXPECT_NEAR(one.at(row, col), expected, 2e-5) << row << " " << col;
    }
  }

  auto differing = [](const DepthImage& a, const DepthImage& b) {
    size_t n = 0;
    for (size_t i = 0; i < a.data.size(); ++i) n += a.data[i] != b.data[i] ? 1 : 0;
    return n;
  };
  const DepthImage next_frame = render(*scene, config, Transform::Identity(), 2, 10);
  EXPECT_GT(differing(one, next_frame), 640u * 480u * 99 / 100);
  config.noise_seed = 43;
  const DepthImage other_seed = render(*scene, config, Transform::Identity(), 2, 9);
  EXPECT_GT(differing(one, other_seed), 640u * 480u * 99 / 100);
}

TEST(DepthRenderer, NoisyDepthFunction) {
  EXPECT_EQ(noisyDepth(5.0f, 0.0, 1, 2, 3), 5.0f);
  EXPECT_EQ(noisyDepth(5.0f, 0.01, 1, 2, 3), noisyDepth(5.0f, 0.01, 1, 2, 3));
  EXPECT_NE(noisyDepth(5.0f, 0.01, 1, 2, 3), noisyDepth(5.0f, 0.01, 1, 2, 4));
  // The deviation scales with k z^2 for the same draw.
  const double d5 = noisyDepth(5.0f, 0.01, 1, 2, 3) - 5.0;
  const double d2 = noisyDepth(2.0f, 0.01, 1, 2, 3) - 2.0;
  ASSERT_GT(std::abs(d5), 1e-4);
  EXPECT_NEAR(d2 / d5, 4.0 / 25.0, 1e-4);
}

TEST(DepthRenderer, NoisyDepthsOutsideTheRangeAreDropped) {
  const auto scene = buildScene(planeAtZ(7.5));
  ASSERT_NE(scene, nullptr);
  CameraConfig config;
  config.noise_k = 0.01;
  const DepthImage image = render(*scene, config, Transform::Identity(), 2);
  for (float z : image.data) {
    if (std::isfinite(z)) {
      ASSERT_LE(z, 8.0f);
    }
  }
  // P(7.5 + 0.5625 g > 8) = 1 - Phi(0.8889) = 0.1870.
  const double dropped = 1.0 - static_cast<double>(image.validCount()) / image.data.size();
  EXPECT_NEAR(dropped, 0.1870, 0.005);
}

// ---- (h) back-projection ----

TEST(DepthRenderer, DepthToPointsLieOnThePlane) {
  const TiltedPlane plane;
  const CameraConfig config;
  const DepthCamera cam(config);
  const auto scene = buildScene(plane.mesh(Transform::Identity()));
  ASSERT_NE(scene, nullptr);
  const DepthImage image = render(*scene, config, Transform::Identity());
  std::vector<Eigen::Vector3f> points;
  ASSERT_TRUE(depthToPoints(cam, image, &points));
  ASSERT_EQ(points.size(), image.validCount());
  ASSERT_GT(points.size(), 200000u);
  size_t i = 0;
  for (int row = 0; row < cam.height(); ++row) {
    for (int col = 0; col < cam.width(); ++col) {
      const float z = image.at(row, col);
      if (!std::isfinite(z)) continue;
      const Eigen::Vector3f& p = points[i++];
      ASSERT_EQ(p.z(), z) << col << " " << row;
      ASSERT_NEAR(p.x(), (col - cam.cx()) / cam.fx() * z, 1e-5);
      ASSERT_NEAR(p.y(), (row - cam.cy()) / cam.fy() * z, 1e-5);
      ASSERT_NEAR(plane.n_C.dot(p.cast<double>()), plane.d_C, 1e-4) << col << " " << row;
    }
  }
  EXPECT_EQ(i, points.size());

  std::vector<Eigen::Vector3f> strided;
  ASSERT_TRUE(depthToPoints(cam, image, &strided, 3));
  size_t expected = 0;
  for (int row = 0; row < cam.height(); row += 3) {
    for (int col = 0; col < cam.width(); col += 3) expected += std::isfinite(image.at(row, col)) ? 1 : 0;
  }
  EXPECT_EQ(strided.size(), expected);
}

TEST(DepthRenderer, DepthToPointsRejectsSizeMismatch) {
  const DepthCamera cam{CameraConfig()};
  DepthImage image;
  image.resize(320, 240);
  image.data.assign(image.data.size(), 3.0f);
  std::vector<Eigen::Vector3f> points(5, Eigen::Vector3f::Ones());
  EXPECT_FALSE(depthToPoints(cam, image, &points));
  EXPECT_TRUE(points.empty());
  image.resize(640, 479);
  points.assign(2, Eigen::Vector3f::Ones());
  EXPECT_FALSE(depthToPoints(cam, image, &points));
  EXPECT_TRUE(points.empty());
}

// ---- (i) procedural scenes in the world frame ----

TEST(DepthRenderer, ProceduralBoxFromMinusX) {
  TriangleMesh mesh;
  ASSERT_TRUE(makeProceduralScene("box", &mesh).ok());
  const auto scene = buildScene(mesh);
  ASSERT_NE(scene, nullptr);
  Transform T = Transform::Identity();
  T.linear().col(0) = Vector3d(0, -1, 0);
  T.linear().col(1) = Vector3d(0, 0, -1);
  T.linear().col(2) = Vector3d(1, 0, 0);
  T.translation() = Vector3d(-6, 0, 2);
  EXPECT_TRUE(T.isApprox(lookAlong(Vector3d(-6, 0, 2), Vector3d::UnitX())));
  const DepthImage image = render(*scene, CameraConfig(), T, 2);
  for (int row : {239, 240}) {
    for (int col : {319, 320}) EXPECT_NEAR(image.at(row, col), 4.0, 1e-5) << row << " " << col;
  }
  // The face x = -2 spans |x / z| <= 0.5 (columns 160..479) and |y / z| <=
  // 0.5 (rows 32..447), all at depth 4.
  EXPECT_EQ(image.validCount(), 320u * 416u);
  EXPECT_EQ(countOff(image, 4.0, 1e-5), 640u * 480u - 320u * 416u);
  EXPECT_EQ(image.at(240, 159), std::numeric_limits<float>::infinity());
  EXPECT_NEAR(image.at(240, 160), 4.0, 1e-5);
  EXPECT_NEAR(image.at(240, 479), 4.0, 1e-5);
  EXPECT_EQ(image.at(240, 480), std::numeric_limits<float>::infinity());
  EXPECT_EQ(image.at(31, 320), std::numeric_limits<float>::infinity());
  EXPECT_NEAR(image.at(32, 320), 4.0, 1e-5);
  EXPECT_NEAR(image.at(447, 320), 4.0, 1e-5);
  EXPECT_EQ(image.at(448, 320), std::numeric_limits<float>::infinity());
  // World y = +2 (left of the camera) is on the left: column 160.
  EXPECT_TRUE(std::isfinite(image.at(240, 160)));
}

TEST(DepthRenderer, ProceduralSphereFromMinusX) {
  TriangleMesh mesh;
  ASSERT_TRUE(makeProceduralScene("sphere", &mesh).ok());
  const auto scene = buildScene(mesh);
  ASSERT_NE(scene, nullptr);
  const CameraConfig config = oddCamera();
  const DepthImage image = render(*scene, config, lookAlong(Vector3d(-6, 0, 2), Vector3d::UnitX()));
  // Radius 2 at distance 6; 32 rings x 64 segments give facets at most
  // 2 (1 - cos(pi / 16)) = 0.038 m inside the sphere.
  const float zc = image.at(60, 80);
  EXPECT_GE(zc, 4.0 - 1e-5);
  EXPECT_LE(zc, 4.0 + 2.0 * (1.0 - std::cos(M_PI / 16)));
}

TEST(DepthRenderer, ProceduralRoomPillarTooCloseIsNotSeenThrough) {
  TriangleMesh mesh;
  ASSERT_TRUE(makeProceduralScene("room", &mesh).ok());
  const auto scene = buildScene(mesh);
  ASSERT_NE(scene, nullptr);
  const DepthImage image = render(*scene, CameraConfig(), lookAlong(Vector3d(0, 0, 2), Vector3d::UnitX()));
  // Straight ahead: the wall x = 5.
  EXPECT_NEAR(image.at(239, 319), 5.0, 1e-5);
  EXPECT_NEAR(image.at(240, 320), 5.0, 1e-5);
  // The left edge column meets the pillar face x = 1.5 at y = 1.497: 1.5 m is
  // below the 1.6 m minimum range, so no return (not the wall behind it).
  EXPECT_EQ(image.at(240, 0), -std::numeric_limits<float>::infinity());  // REP 117 too close
  // The right edge column meets the wall y = -4 at depth 4 / 0.9984.
  EXPECT_NEAR(image.at(240, 639), 4.0 / (319.5 / 320.0), 1e-4);
}

}  // namespace
}  // namespace surface_nbv
