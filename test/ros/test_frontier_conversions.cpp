// SurfaceFrontier <-> Frontier: a round trip keeps what the planner reads,
// and a message with a value out of its range is refused with its name.
#include "surface_nbv/ros/frontier_conversions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace surface_nbv;

namespace {

Frontier twoViewpoints() {
  Frontier f;
  for (int i = 0; i < 2; ++i) {
    Ise ise;
    ise.position = Eigen::Vector3d(i, 1.0, 2.0);
    ise.viewpoint = i;
    f.ises.push_back(ise);
    Viewpoint v;
    v.position = Eigen::Vector3d(i, -3.0, 2.0);
    v.yaw = 0.5 * i;
    v.visible = {static_cast<uint32_t>(i)};
    v.sources = {static_cast<uint32_t>(i)};
    v.cluster = 0;
    v.unknown_fraction = i == 0 ? 0.02 : 0.75;
    f.viewpoints.push_back(v);
  }
  Cluster c;
  c.viewpoints = {0, 1};
  c.visible_ises = 2;
  c.gain = 1.0;
  f.clusters.push_back(c);
  return f;
}

}  // namespace

TEST(FrontierConversions, RoundTripKeepsTheUnknownFraction) {
  surface_nbv::SurfaceFrontier msg;
  toFrontierMsg(twoViewpoints(), std_msgs::Header(), &msg);
  ASSERT_EQ(msg.viewpoints.size(), 2u);
  EXPECT_EQ(msg.viewpoints[0].unknown_fraction, 0.02);
  Frontier back;
  ASSERT_TRUE(fromFrontierMsg(msg, &back).ok());
  ASSERT_EQ(back.viewpoints.size(), 2u);
  EXPECT_EQ(back.viewpoints[0].unknown_fraction, 0.02);
  EXPECT_EQ(back.viewpoints[1].unknown_fraction, 0.75);
  EXPECT_NEAR(back.viewpoints[1].yaw, 0.5, 1e-12);
}

TEST(FrontierConversions, UnknownFractionOutsideZeroToOneIsRefused) {
  for (double bad : {-0.1, 1.5, std::nan(""), HUGE_VAL}) {
    surface_nbv::SurfaceFrontier msg;
    toFrontierMsg(twoViewpoints(), std_msgs::Header(), &msg);
    msg.viewpoints[1].unknown_fraction = bad;
    Frontier back;
    const Status s = fromFrontierMsg(msg, &back);
    ASSERT_FALSE(s.ok()) << bad;
    EXPECT_NE(s.message().find("viewpoint 1 unknown_fraction"), std::string::npos) << s.message();
  }
}
