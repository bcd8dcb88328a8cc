#include "surface_nbv/map/pose_queue.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace surface_nbv;

namespace {

// A straight flight at constant velocity, turning at a constant rate about a
// fixed axis: linear interpolation and slerp reproduce it exactly.
Transform straightMotion(double s) {
  const Eigen::Quaterniond q0(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  Transform T = Transform::Identity();
  T.linear() = (Eigen::AngleAxisd(0.8 * s, Eigen::Vector3d(0.2, -0.5, 1.0).normalized()) * q0).toRotationMatrix();
  T.translation() = Eigen::Vector3d(1.0, -2.0, 3.0) + s * Eigen::Vector3d(1.5, 0.25, -0.5);
  return T;
}

Transform translation(double x) {
  Transform T = Transform::Identity();
  T.translation().x() = x;
  return T;
}

void expectPoseNear(const Transform& expected, const Transform& actual, double tol) {
  EXPECT_TRUE(expected.translation().isApprox(actual.translation(), tol))
      << expected.translation().transpose() << " vs " << actual.translation().transpose();
  EXPECT_LT((expected.linear() - actual.linear()).norm(), tol);
}

}  // namespace

TEST(PoseQueue, ConfigValidation) {
  EXPECT_TRUE(PoseQueueConfig().validate().ok());
  PoseQueueConfig c;
  c.capacity = 1;
  EXPECT_NE(c.validate().message().find("capacity"), std::string::npos);
  c = PoseQueueConfig();
  c.max_interval = 0.0;
  EXPECT_NE(c.validate().message().find("max_interval"), std::string::npos);
  c = PoseQueueConfig();
  c.reset_tolerance = std::nan("");
  EXPECT_NE(c.validate().message().find("reset_tolerance"), std::string::npos);
}

TEST(PoseQueue, InterpolationIsExactOnAStraightMotion) {
  PoseQueue queue;
  for (int i = 0; i <= 20; ++i) ASSERT_TRUE(queue.add(100.0 + 0.1 * i, straightMotion(0.1 * i)).ok());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> s(0.0, 2.0);
  for (int k = 0; k < 200; ++k) {
    const double at = s(rng);
    Transform T;
    ASSERT_EQ(queue.lookup(100.0 + at, &T), PoseLookup::kFound) << at;
    expectPoseNear(straightMotion(at), T, 1e-9);
  }
  Transform T;
  ASSERT_EQ(queue.lookup(100.0, &T), PoseLookup::kFound);
  expectPoseNear(straightMotion(0.0), T, 1e-12);
  ASSERT_EQ(queue.lookup(102.0, &T), PoseLookup::kFound);
  expectPoseNear(straightMotion(2.0), T, 1e-12);
}

TEST(PoseQueue, NewerThanTheNewestIsNotYetNeverAnExtrapolation) {
  PoseQueueConfig config;
  config.max_interval = 1.0;
  PoseQueue queue(config);
  Transform T = translation(42.0);
  EXPECT_EQ(queue.lookup(1.0, &T), PoseLookup::kNotYet);
  ASSERT_TRUE(queue.add(1.0, translation(1.0)).ok());
  ASSERT_TRUE(queue.add(2.0, translation(2.0)).ok());
  EXPECT_EQ(queue.lookup(2.0 + 1e-9, &T), PoseLookup::kNotYet);
  EXPECT_EQ(T.translation().x(), 42.0);  // untouched unless found
  ASSERT_TRUE(queue.add(3.0, translation(3.0)).ok());
  ASSERT_EQ(queue.lookup(2.5, &T), PoseLookup::kFound);
  EXPECT_DOUBLE_EQ(T.translation().x(), 2.5);
}

TEST(PoseQueue, OlderThanTheOldestKeptIsTooOldAndTheQueueIsBounded) {
  PoseQueueConfig config;
  config.capacity = 10;
  PoseQueue queue(config);
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(queue.add(0.01 * i, translation(i)).ok());
  EXPECT_EQ(queue.size(), 10u);
  EXPECT_DOUBLE_EQ(queue.oldest(), 0.90);
  EXPECT_DOUBLE_EQ(queue.newest(), 0.99);
  Transform T;
  EXPECT_EQ(queue.lookup(0.5, &T), PoseLookup::kTooOld);
  EXPECT_EQ(queue.lookup(0.8999, &T), PoseLookup::kTooOld);
  EXPECT_EQ(queue.lookup(0.905, &T), PoseLookup::kFound);
  EXPECT_NEAR(T.translation().x(), 90.5, 1e-9);
  EXPECT_EQ(queue.lookup(std::nan(""), &T), PoseLookup::kTooOld);
  EXPECT_EQ(queue.resets(), 0u);
}

TEST(PoseQueue, ClockGoingBackResetsInsteadOfFreezing) {
  PoseQueue queue;  // reset_tolerance 1 s
  for (int i = 0; i <= 100; ++i) ASSERT_TRUE(queue.add(10.0 + 0.1 * i, translation(i)).ok());
  // Out of order within the tolerance: slotted in, no reset.
  ASSERT_TRUE(queue.add(19.55, translation(-1.0)).ok());
  EXPECT_EQ(queue.resets(), 0u);
  EXPECT_EQ(queue.size(), 102u);
  Transform T;
  ASSERT_EQ(queue.lookup(19.55, &T), PoseLookup::kFound);
  EXPECT_EQ(T.translation().x(), -1.0);
  // A bag restarted: the clock is back at 10.5 s.
  ASSERT_TRUE(queue.add(10.5, translation(7.0)).ok());
  EXPECT_EQ(queue.resets(), 1u);
  EXPECT_EQ(queue.size(), 1u);
  EXPECT_EQ(queue.lookup(15.0, &T), PoseLookup::kNotYet);  // the old run's poses are gone
  EXPECT_EQ(queue.lookup(10.4, &T), PoseLookup::kTooOld);
  ASSERT_TRUE(queue.add(10.6, translation(8.0)).ok());
  ASSERT_EQ(queue.lookup(10.55, &T), PoseLookup::kFound);
  EXPECT_NEAR(T.translation().x(), 7.5, 1e-9);
}

TEST(PoseQueue, SameStampReplaces) {
  PoseQueue queue;
  ASSERT_TRUE(queue.add(1.0, translation(1.0)).ok());
  ASSERT_TRUE(queue.add(1.0, translation(5.0)).ok());
  EXPECT_EQ(queue.size(), 1u);
  Transform T;
  ASSERT_EQ(queue.lookup(1.0, &T), PoseLookup::kFound);
  EXPECT_EQ(T.translation().x(), 5.0);
}

TEST(PoseQueue, PosesTooFarApartDoNotBracketAStamp) {
  PoseQueue queue;  // max_interval 0.5 s
  ASSERT_TRUE(queue.add(0.0, translation(0.0)).ok());
  ASSERT_TRUE(queue.add(0.5, translation(1.0)).ok());
  ASSERT_TRUE(queue.add(2.0, translation(2.0)).ok());
  Transform T;
  EXPECT_EQ(queue.lookup(0.25, &T), PoseLookup::kFound);
  EXPECT_EQ(queue.lookup(1.0, &T), PoseLookup::kGap);
  EXPECT_EQ(queue.lookup(2.0, &T), PoseLookup::kFound);
  EXPECT_STREQ(toString(PoseLookup::kGap), "gap");
}

TEST(PoseQueue, RefusesNonFiniteAndNonRigidPoses) {
  PoseQueue queue;
  ASSERT_TRUE(queue.add(1.0, translation(1.0)).ok());
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  Transform bad = translation(nan);
  EXPECT_FALSE(queue.add(2.0, bad).ok());
  bad = Transform::Identity();
  bad.linear()(1, 2) = nan;
  EXPECT_FALSE(queue.add(2.0, bad).ok());
  EXPECT_FALSE(queue.add(nan, translation(2.0)).ok());
  EXPECT_FALSE(queue.add(inf, translation(2.0)).ok());
  bad = Transform::Identity();
  bad.linear() *= 1.01;  // scaled
  EXPECT_FALSE(queue.add(2.0, bad).ok());
  bad = Transform::Identity();
  bad.linear()(2, 2) = -1.0;  // a reflection
  EXPECT_FALSE(queue.add(2.0, bad).ok());
  EXPECT_EQ(queue.size(), 1u);
  EXPECT_EQ(queue.newest(), 1.0);
  Transform T;
  EXPECT_EQ(queue.lookup(1.5, &T), PoseLookup::kNotYet);
}
