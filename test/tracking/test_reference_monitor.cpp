// nbv_planner's off-track rule (tracking/reference_monitor.h).
#include "surface_nbv/tracking/reference_monitor.h"

#include <gtest/gtest.h>

using namespace surface_nbv;

namespace {

std::vector<std::pair<double, Eigen::Vector3d>> straightLeg() {
  return {{0.0, Eigen::Vector3d(0, 0, 2)}, {10.0, Eigen::Vector3d(10, 0, 2)}};
}

}  // namespace

TEST(ReferenceMonitor, MeasuresTheDistanceToTheReferenceOfTheMoment) {
  ReferenceMonitor m(3.0, 2.0);
  EXPECT_DOUBLE_EQ(m.error(5.0, Eigen::Vector3d(100, 0, 0)), 0.0);  // no reference yet
  m.setReference(straightLeg());
  EXPECT_NEAR(m.error(0.0, Eigen::Vector3d(0, 0, 2)), 0.0, 1e-12);
  EXPECT_NEAR(m.error(5.0, Eigen::Vector3d(5, 1, 2)), 1.0, 1e-12);   // halfway along
  EXPECT_NEAR(m.error(25.0, Eigen::Vector3d(10, 0, 0)), 2.0, 1e-12);  // after its end: the last point
  EXPECT_NEAR(m.error(-1.0, Eigen::Vector3d(0, 0, 3)), 1.0, 1e-12);   // before its start: the first
}

TEST(ReferenceMonitor, OffTrackOnlyAfterStayingAwayForTheHoldTime) {
  ReferenceMonitor m(3.0, 2.0);
  m.setReference(straightLeg());
  double e = 0.0;
  const Eigen::Vector3d stuck(0, 0, 2);  // a tracker that never moved
  EXPECT_FALSE(m.offTrack(2.0, stuck, &e));  // 2 m behind: within 3 m
  EXPECT_NEAR(e, 2.0, 1e-12);
  EXPECT_FALSE(m.offTrack(4.0, stuck, &e));  // 4 m behind: off since 4 s
  EXPECT_FALSE(m.offTrack(5.9, stuck, &e));
  EXPECT_TRUE(m.offTrack(6.0, stuck, &e));
  // Back on track resets the clock; a new reference does too.
  EXPECT_FALSE(m.offTrack(6.5, Eigen::Vector3d(6.5, 0, 2), &e));
  EXPECT_FALSE(m.offTrack(7.0, stuck, &e));
  EXPECT_FALSE(m.offTrack(8.5, stuck, &e));
  m.setReference(straightLeg());
  EXPECT_FALSE(m.offTrack(9.0, stuck, &e));
  EXPECT_TRUE(m.offTrack(11.0, stuck, &e));
}

TEST(ReferenceMonitor, ZeroMaxErrorTurnsTheCheckOff) {
  ReferenceMonitor m(0.0, 2.0);
  m.setReference(straightLeg());
  double e = 1.0;
  for (double t = 0.0; t < 20.0; t += 1.0) EXPECT_FALSE(m.offTrack(t, Eigen::Vector3d(-50, 0, 0), &e));
  EXPECT_DOUBLE_EQ(e, 0.0);
}
