#include "surface_nbv/tracking/trajectory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace surface_nbv;

namespace {

TrajectoryPoint point(double t, double x, double y = 0.0, double yaw = 0.0) {
  TrajectoryPoint q;
  q.t = t;
  q.p_W = Eigen::Vector3d(x, y, 1.0);
  q.yaw = yaw;
  return q;
}

const Eigen::Vector3d kStart(0, 0, 1);

}  // namespace

TEST(Trajectory, RefusesBadTrajectoriesWithAReason) {
  EXPECT_NE(Trajectory().validate(kStart, 2.0).message().find("empty"), std::string::npos);

  Trajectory nan({point(0, 0), point(1, std::numeric_limits<double>::quiet_NaN())});
  EXPECT_NE(nan.validate(kStart, 2.0).message().find("point 1"), std::string::npos);

  TrajectoryPoint bad_velocity = point(1, 1);
  bad_velocity.has_velocity = true;
  bad_velocity.v_W.y() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(Trajectory({point(0, 0), bad_velocity}).validate(kStart, 2.0));

  Trajectory backwards({point(0, 0), point(2, 1), point(1, 2)});
  EXPECT_NE(backwards.validate(kStart, 2.0).message().find("increase"), std::string::npos);
  EXPECT_FALSE(Trajectory({point(0, 0), point(0, 1)}).validate(kStart, 2.0));

  Trajectory far({point(0, 5), point(1, 6)});
  EXPECT_NE(far.validate(kStart, 2.0).message().find("from the UAV"), std::string::npos);
  EXPECT_TRUE(far.validate(Eigen::Vector3d(4, 0, 1), 2.0));

  EXPECT_FALSE(Trajectory({point(0, 0), point(1, 1e7)}).validate(kStart, 2.0));
  EXPECT_TRUE(Trajectory({point(0, 0), point(1, 1), point(3, 1)}).validate(kStart, 2.0));
}

TEST(Trajectory, SampleInterpolatesAndHoldsTheEnds) {
  Trajectory traj({point(1, 0, 0, 3.0), point(3, 2, 0, -3.0)});
  TrajectorySample s = traj.sample(0.0);
  EXPECT_TRUE(s.p_W.isApprox(Eigen::Vector3d(0, 0, 1)));
  EXPECT_EQ(s.v_W.norm(), 0.0);
  s = traj.sample(2.0);
  EXPECT_TRUE(s.p_W.isApprox(Eigen::Vector3d(1, 0, 1)));
  EXPECT_TRUE(s.v_W.isApprox(Eigen::Vector3d(1, 0, 0)));
  // Yaw from 3 to -3 goes the short way, through pi.
  EXPECT_NEAR(std::abs(s.yaw), M_PI, 1e-9);
  s = traj.sample(10.0);
  EXPECT_TRUE(s.p_W.isApprox(Eigen::Vector3d(2, 0, 1)));
  EXPECT_EQ(s.v_W.norm(), 0.0);
}

TEST(Trajectory, GivenVelocitiesAreInterpolated) {
  TrajectoryPoint a = point(0, 0), b = point(2, 1);
  a.has_velocity = b.has_velocity = true;
  a.v_W = Eigen::Vector3d(0, 0, 0);
  b.v_W = Eigen::Vector3d(1, 0, 0);
  EXPECT_TRUE(Trajectory({a, b}).sample(1.0).v_W.isApprox(Eigen::Vector3d(0.5, 0, 0)));
}

TEST(Trajectory, TimeWaypointsAtHalfAMetrePerSecond) {
  std::vector<Waypoint> w(4);
  w[0].p_W = Eigen::Vector3d(0, 0, 1);
  w[1].p_W = Eigen::Vector3d(3, 0, 1);
  w[2].p_W = Eigen::Vector3d(3, 0, 1);  // repeated: skipped
  w[3].p_W = Eigen::Vector3d(3, 0, 1);
  w[3].yaw = 1.0;                       // a pure rotation of 1 rad at 0.5 rad/s
  const Trajectory traj = timeWaypoints(w, 10.0);
  ASSERT_EQ(traj.size(), 3u);
  EXPECT_DOUBLE_EQ(traj.startTime(), 10.0);
  EXPECT_DOUBLE_EQ(traj.points()[1].t, 16.0);
  EXPECT_DOUBLE_EQ(traj.endTime(), 18.0);
  EXPECT_NEAR(traj.sample(13.0).v_W.norm(), 0.5, 1e-12);
  Trajectory shifted = traj;
  shifted.shiftTimes(-10.0);
  EXPECT_DOUBLE_EQ(shifted.endTime(), 8.0);
}
