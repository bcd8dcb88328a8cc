#include "surface_nbv/tracking/uav_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace surface_nbv;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

TEST(UavModel, ConfigNamesBadKey) {
  EXPECT_TRUE(UavModelConfig().validate());
  UavModelConfig c;
  c.v_max = 0.0;
  EXPECT_NE(c.validate().message().find("v_max"), std::string::npos);
  c = UavModelConfig();
  c.drag = kNaN;
  EXPECT_NE(c.validate().message().find("drag"), std::string::npos);
  c = UavModelConfig();
  c.yaw_rate_max = -1;
  EXPECT_NE(c.validate().message().find("yaw_rate_max"), std::string::npos);
}

// The legs' reference within the UAV's limits: at the limit passes, above it
// is refused naming both keys, an unknown (infinite) limit passes.
TEST(UavModel, ReferenceWithinLimitsNamesTheKeyOverItsLimit) {
  EXPECT_TRUE(checkReferenceWithinLimits(1.0, 1.0, 1.0, 1.0, "mission/", "tracker/").ok());
  Status s = checkReferenceWithinLimits(1.2, 0.5, 1.0, 1.0, "mission/", "tracker/");
  EXPECT_NE(s.message().find("mission/speed expected <= tracker/v_max"), std::string::npos) << s.message();
  s = checkReferenceWithinLimits(0.5, 1.5, 1.0, 1.0, "/planner/", "/tracker/");
  EXPECT_NE(s.message().find("/planner/yaw_rate expected <= /tracker/yaw_rate_max"), std::string::npos)
      << s.message();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(checkReferenceWithinLimits(20.0, 10.0, inf, inf, "a/", "b/").ok());
}

// The exact discretization matches many tiny Euler steps, with and without drag.
TEST(UavModel, DiscretizationMatchesFineIntegration) {
  for (double drag : {0.0, 0.3}) {
    const AxisDiscretization d = discretizeAxis(drag, 0.5);
    double p = 0.2, v = 0.4;
    const double a = 0.7;
    for (int i = 0; i < 500000; ++i) {
      const double h = 0.5 / 500000;
      p += h * v + 0.5 * h * h * (a - drag * v);
      v += h * (a - drag * v);
    }
    EXPECT_NEAR(0.4 * d.alpha + d.beta * a, v, 1e-6) << "drag " << drag;
    EXPECT_NEAR(0.2 + d.beta * 0.4 + d.gamma * a, p, 1e-6) << "drag " << drag;
  }
}

TEST(UavModel, CommandsAreClampedAndStateStaysInLimits) {
  UavModelConfig c;
  UavModel model(c);
  const double bad[] = {kNaN, 1e300, -1e300, std::numeric_limits<double>::infinity(), 0.3};
  for (int i = 0; i < 2000; ++i) {
    UavCommand u;
    u.a_W = Eigen::Vector3d(bad[i % 5], bad[(i + 1) % 5], bad[(i + 3) % 5]);
    u.yaw_rate = bad[(i + 2) % 5];
    const UavCommand applied = model.step(u, 0.01);
    ASSERT_TRUE(applied.a_W.allFinite());
    ASSERT_LE(applied.a_W.cwiseAbs().maxCoeff(), c.a_max);
    ASSERT_LE(std::abs(applied.yaw_rate), c.yaw_rate_max);
    ASSERT_TRUE(model.state().allFinite());
    ASSERT_LE(model.state().v_W.cwiseAbs().maxCoeff(), c.v_max + 1e-12);
    ASSERT_LE(std::abs(model.state().yaw), M_PI);
  }
  UavState s;
  s.p_W.x() = kNaN;
  EXPECT_FALSE(model.reset(s));
  EXPECT_TRUE(model.state().allFinite());
}

// A full-throttle command reaches v_max and stops there; the drag makes a
// released UAV coast down as exp(-drag t).
TEST(UavModel, SaturatesAtVmaxAndCoastsWithDrag) {
  UavModelConfig c;
  UavModel model(c);
  UavCommand full;
  full.a_W = Eigen::Vector3d(10, 0, 0);
  for (int i = 0; i < 300; ++i) model.step(full, 0.01);
  EXPECT_NEAR(model.state().v_W.x(), c.v_max, 1e-12);
  for (int i = 0; i < 100; ++i) model.step(UavCommand(), 0.01);
  EXPECT_NEAR(model.state().v_W.x(), c.v_max * std::exp(-c.drag * 1.0), 1e-9);
}

TEST(UavModel, ClampAccelerationBrakesWhenAboveTheBox) {
  const AxisDiscretization d = discretizeAxis(0.0, 0.1);
  EXPECT_DOUBLE_EQ(clampAcceleration(5.0, 0.0, 1.0, 1.5, d), -1.5);
  EXPECT_DOUBLE_EQ(clampAcceleration(-5.0, kNaN, 1.0, 1.5, d), 1.5);
  EXPECT_NEAR(clampAcceleration(0.95, 1.5, 1.0, 1.5, d), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(clampAcceleration(0.0, 0.4, 1.0, 1.5, d), 0.4);
}

TEST(UavModel, WrapAngle) {
  EXPECT_NEAR(wrapAngle(3 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(wrapAngle(-M_PI), M_PI, 1e-12);
  EXPECT_NEAR(wrapAngle(1e6), std::remainder(1e6, 2 * M_PI), 1e-9);
  EXPECT_EQ(wrapAngle(kNaN), 0.0);
}
