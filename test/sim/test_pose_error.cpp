// The odometry error model (pose_error.h): a seeded random walk per metre
// flown in position and yaw, and per-frame jitter.
#include "surface_nbv/sim/pose_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace surface_nbv {
namespace {

using Eigen::Vector3d;

Transform poseAt(const Vector3d& p, double yaw) {
  Transform T = Transform::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = p;
  return T;
}

// Flies the estimate along x in steps of `step` metres for `length` metres.
PoseErrorModel flyStraight(const PoseErrorConfig& c, double length, double step = 0.1) {
  PoseErrorModel m(c);
  const int n = static_cast<int>(std::lround(length / step));
  for (int k = 0; k <= n; ++k) m.advance(Vector3d(k * step, 2.0, 3.0), static_cast<uint64_t>(k));
  return m;
}

bool sameTransform(const Transform& a, const Transform& b) { return a.matrix() == b.matrix(); }

TEST(PoseError, OffLeavesEveryPoseUntouched) {
  PoseErrorConfig c;
  EXPECT_FALSE(c.enabled());
  PoseErrorModel m(c);
  const Transform T = poseAt(Vector3d(1.25, -3.5, 2.0), 0.7);
  for (int k = 0; k < 10; ++k) m.advance(Vector3d(k, 0, 0), k);
  EXPECT_TRUE(sameTransform(m.truePose(T), T));
  EXPECT_TRUE(sameTransform(m.reportedPose(T, 3), T));
  EXPECT_EQ(m.stats().frames, 0u);
}

TEST(PoseError, TheWalkIsAPureFunctionOfSeedAndFrame) {
  PoseErrorConfig c;
  c.drift_rate = 0.005;
  c.yaw_drift_deg = 0.05;
  c.jitter_position = 0.01;
  c.jitter_angle_deg = 0.1;
  c.seed = 7;
  const PoseErrorModel a = flyStraight(c, 50.0), b = flyStraight(c, 50.0);
  EXPECT_TRUE(sameTransform(a.drift(), b.drift()));
  const Transform T = poseAt(Vector3d(50, 2, 3), 0.0);
  EXPECT_TRUE(sameTransform(a.reportedPose(T, 9), b.reportedPose(T, 9)));
  EXPECT_FALSE(sameTransform(a.reportedPose(T, 9), a.reportedPose(T, 10)));
  c.seed = 8;
  EXPECT_FALSE(sameTransform(a.drift(), flyStraight(c, 50.0).drift()));
  EXPECT_GT(a.stats().final_position, 0.0);
  EXPECT_NEAR(a.distance(), 50.0, 1e-9);
}

TEST(PoseError, PositionErrorGrowsWithTheSquareRootOfTheDistance) {
  // 400 seeds: per axis sd = rate sqrt(d), within 10 % (sd of an sd estimate
  // from 400 draws: 3.5 %).
  PoseErrorConfig c;
  c.drift_rate = 0.005;
  for (double length : {25.0, 100.0}) {
    double sum2 = 0.0;
    const int n = 400;
    for (int s = 0; s < n; ++s) {
      c.seed = 1000 + s;
      const PoseErrorModel m = flyStraight(c, length, 0.25);
      const Vector3d e = m.truePose(poseAt(Vector3d(length, 2, 3), 0)).translation() - Vector3d(length, 2, 3);
      sum2 += e.squaredNorm() / 3.0;
      EXPECT_NEAR(m.stats().final_position, e.norm(), 1e-12);
      EXPECT_DOUBLE_EQ(m.driftYaw(), 0.0);
    }
    EXPECT_NEAR(std::sqrt(sum2 / n), 0.005 * std::sqrt(length), 0.1 * 0.005 * std::sqrt(length)) << length;
  }
}

TEST(PoseError, YawDriftTurnsTheMotionAfterItNotThePositionAtIt) {
  PoseErrorConfig c;
  c.yaw_drift_deg = 0.5;
  c.seed = 3;
  PoseErrorModel m(c);
  Vector3d last_true = Vector3d::Zero();
  double max_jump = 0.0;
  for (int k = 0; k <= 1000; ++k) {
    const Vector3d p(0.1 * k, 0.0, 2.0);
    m.advance(p, k);
    const Vector3d truth = m.truePose(poseAt(p, 0.0)).translation();
    if (k > 0) max_jump = std::max(max_jump, std::abs((truth - last_true).norm() - 0.1));
    last_true = truth;
  }
  // Each 0.1 m step of the estimate is a 0.1 m step of the truth, turned.
  EXPECT_LT(max_jump, 1e-9);
  const Transform T_true = m.truePose(poseAt(Vector3d(100, 0, 2), 0.0));
  const double yaw = std::atan2(T_true.linear()(1, 0), T_true.linear()(0, 0));
  EXPECT_NEAR(yaw, m.driftYaw(), 1e-9);
  EXPECT_GT(std::abs(m.driftYaw()), 0.5 * M_PI / 180.0);  // 0.5 deg sqrt(100): 5 deg sd
  // The heading error moved the truth sideways: about the yaw times the distance.
  EXPECT_GT(m.stats().final_position, 0.1);
  EXPECT_NEAR(T_true.translation().z(), 2.0, 1e-9);  // yaw only: the height stays
}

TEST(PoseError, JitterIsPerFrameAndLeavesTheTruthAlone) {
  PoseErrorConfig c;
  c.jitter_position = 0.01;
  c.jitter_angle_deg = 0.2;
  PoseErrorModel m(c);
  const Transform T = poseAt(Vector3d(1, 2, 3), 0.3);
  double sum2 = 0.0, angle2 = 0.0;
  const int n = 3000;
  for (int k = 0; k < n; ++k) {
    m.advance(Vector3d(1 + 0.1 * k, 2, 3), k);
    EXPECT_TRUE(sameTransform(m.truePose(T), T));  // no drift configured
    const Transform J = T.inverse() * m.reportedPose(T, k);
    sum2 += J.translation().squaredNorm() / 3.0;
    angle2 += std::pow(Eigen::AngleAxisd(J.linear()).angle(), 2) / 3.0;
  }
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.01, 0.001);
  EXPECT_NEAR(std::sqrt(angle2 / n) * 180.0 / M_PI, 0.2, 0.02);
}

TEST(PoseError, BadFieldsAreNamed) {
  PoseErrorConfig c;
  c.drift_rate = -0.1;
  EXPECT_EQ(c.validate().message().rfind("pose_drift_rate", 0), 0u);
  c = PoseErrorConfig();
  c.yaw_drift_deg = std::nan("");
  EXPECT_EQ(c.validate().message().rfind("pose_yaw_drift_deg", 0), 0u);
  c = PoseErrorConfig();
  c.jitter_position = 2.0;
  EXPECT_EQ(c.validate().message().rfind("pose_jitter", 0), 0u);
  c = PoseErrorConfig();
  c.jitter_angle_deg = -1.0;
  EXPECT_EQ(c.validate().message().rfind("pose_jitter_deg", 0), 0u);
  EXPECT_TRUE(PoseErrorConfig().validate().ok());
}

}  // namespace
}  // namespace surface_nbv
