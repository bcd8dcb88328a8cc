// profileFlight on synthetic trajectories sampled every 0.2 s (the mission's
// 5 Hz frames): each motion lands in its class, yaw is summed across the
// +-pi wrap, the classes add up to the flight time and bad samples are skipped.
#include "surface_nbv/mission/flight_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "surface_nbv/util/angles.h"

using namespace surface_nbv;

namespace {

constexpr double kDt = 0.2;
constexpr double kSpeed = 0.5;  // reference speed [m/s]
constexpr double kTol = 1e-9;

// Samples of a trajectory made of constant-velocity, constant-yaw-rate pieces.
struct Track {
  std::vector<Eigen::Vector4d> poses{Eigen::Vector4d::Zero()};
  std::vector<double> times{0.0};

  // `steps` intervals of kDt at velocity v [m/s] and yaw rate w [rad/s].
  Track& add(const Eigen::Vector3d& v, double w, int steps) {
    for (int i = 0; i < steps; ++i) {
      Eigen::Vector4d q = poses.back();
      q.head<3>() += v * kDt;
      q.w() = wrapAngle(q.w() + w * kDt);
      poses.push_back(q);
      times.push_back(times.back() + kDt);
    }
    return *this;
  }
  FlightProfile profile() const { return profileFlight(poses, times, kSpeed); }
};

void expectClasses(const FlightProfile& p, double cruise, double moving, double turning, double stopped) {
  EXPECT_NEAR(p.cruise_s, cruise, kTol);
  EXPECT_NEAR(p.moving_s, moving, kTol);
  EXPECT_NEAR(p.turning_in_place_s, turning, kTol);
  EXPECT_NEAR(p.stopped_s, stopped, kTol);
}

TEST(FlightProfile, StraightFlightAtReferenceSpeedIsAllCruise) {
  const FlightProfile p = Track().add({kSpeed, 0, 0}, 0.0, 25).profile();
  EXPECT_EQ(p.samples, 25u);
  EXPECT_NEAR(p.flight_s, 5.0, kTol);
  expectClasses(p, 5.0, 0.0, 0.0, 0.0);
  EXPECT_NEAR(p.vertical_s, 0.0, kTol);
  EXPECT_NEAR(p.path_m, 2.5, kTol);
  EXPECT_NEAR(p.total_yaw_rad, 0.0, kTol);
}

TEST(FlightProfile, RotationInPlaceIsTurningAndSumsYawAcrossTheWrap) {
  // 20 steps of 0.2 rad: 4 rad, past +pi; the stored yaw wraps to -2.28.
  const Track track = Track().add({0, 0, 0}, 1.0, 20);
  ASSERT_LT(track.poses.back().w(), 0.0);  // the wrap really happened
  const FlightProfile p = track.profile();
  EXPECT_NEAR(p.flight_s, 4.0, kTol);
  expectClasses(p, 0.0, 0.0, 4.0, 0.0);
  EXPECT_NEAR(p.total_yaw_rad, 4.0, 1e-9);
  EXPECT_NEAR(p.path_m, 0.0, kTol);
}

TEST(FlightProfile, YawFromThreeToMinusThreeIsTheShortWayRound) {
  const FlightProfile p = profileFlight({{0, 0, 0, 3.0}, {0, 0, 0, -3.0}}, {0.0, kDt}, kSpeed);
  EXPECT_NEAR(p.total_yaw_rad, 2.0 * M_PI - 6.0, 1e-12);  // 0.283 rad, not 6
  expectClasses(p, 0.0, 0.0, kDt, 0.0);
}

TEST(FlightProfile, HoveringWithJitterIsStopped) {
  // 5 cm/s drift and 0.1 rad/s yaw wobble: below slow_speed and turn_rate.
  Track track;
  for (int i = 0; i < 10; ++i) track.add({0.05, 0, 0}, 0.1, 1).add({-0.05, 0, 0}, -0.1, 1);
  const FlightProfile p = track.profile();
  EXPECT_NEAR(p.flight_s, 4.0, kTol);
  expectClasses(p, 0.0, 0.0, 0.0, 4.0);
  EXPECT_NEAR(p.vertical_s, 0.0, kTol);
  EXPECT_NEAR(p.total_yaw_rad, 20 * 0.02, 1e-9);
}

TEST(FlightProfile, VerticalClimbIsCruiseAndVertical) {
  const FlightProfile p = Track().add({0, 0, kSpeed}, 0.0, 10).profile();
  expectClasses(p, 2.0, 0.0, 0.0, 0.0);
  EXPECT_NEAR(p.vertical_s, 2.0, kTol);
  EXPECT_NEAR(p.path_m, 1.0, kTol);
}

TEST(FlightProfile, MixedSequenceAddsUpToTheFlightTime) {
  const FlightProfile p = Track()
                              .add({kSpeed, 0, 0}, 0.0, 10)    // 2.0 s cruise
                              .add({0, 0.3, 0}, 0.0, 5)        // 1.0 s moving slower (0.3 < 0.44 m/s)
                              .add({0, 0, -0.3}, 0.0, 5)       // 1.0 s moving slower, descending
                              .add({0, 0, 0}, -1.0, 15)        // 3.0 s turning in place
                              .add({0, 0, 0}, 0.0, 4)          // 0.8 s stopped
                              .add({0.4, 0, 0.3}, 0.5, 6)      // 1.2 s cruise (0.5 m/s), mostly level
                              .add({0.3, 0, 0.4}, 0.0, 3)      // 0.6 s cruise, mostly vertical
                              .profile();
  EXPECT_EQ(p.samples, 48u);
  EXPECT_NEAR(p.flight_s, 9.6, kTol);
  expectClasses(p, 3.8, 2.0, 3.0, 0.8);
  EXPECT_NEAR(p.cruise_s + p.moving_s + p.turning_in_place_s + p.stopped_s, p.flight_s, kTol);
  EXPECT_NEAR(p.vertical_s, 1.6, kTol);
  EXPECT_NEAR(p.total_yaw_rad, 3.0 + 0.6, 1e-9);
  EXPECT_NEAR(p.path_m, 1.0 + 0.3 + 0.3 + 0.6 + 0.3, 1e-9);
}

TEST(FlightProfile, TooFewSamplesGiveZeros) {
  for (const Track& track : {Track(), Track().add({kSpeed, 0, 0}, 0.0, 1)}) {
    Track t = track;
    t.poses.pop_back();
    t.times.pop_back();
    const FlightProfile p = t.profile();
    EXPECT_EQ(p.samples, 0u);
    EXPECT_EQ(p.flight_s, 0.0);
    EXPECT_EQ(p.total_yaw_rad, 0.0);
    EXPECT_EQ(p.path_m, 0.0);
  }
}

TEST(FlightProfile, BadSamplesSkipOnlyTheirIntervals) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // 10 cruise intervals of 0.2 s; sample 3 gets a NaN x (intervals 2-3 and
  // 3-4 skipped) and sample 6 is repeated with its time (a zero interval).
  Track track = Track().add({kSpeed, 0, 0}, 0.0, 10);
  track.poses[3].x() = nan;
  track.poses.insert(track.poses.begin() + 7, track.poses[6]);
  track.times.insert(track.times.begin() + 7, track.times[6]);
  FlightProfile p = track.profile();
  EXPECT_EQ(p.samples, 8u);
  EXPECT_NEAR(p.flight_s, 8 * kDt, kTol);
  expectClasses(p, 8 * kDt, 0.0, 0.0, 0.0);
  EXPECT_NEAR(p.path_m, 8 * kDt * kSpeed, kTol);

  // A time going backwards, a NaN time and a NaN yaw are skipped too.
  track = Track().add({kSpeed, 0, 0}, 0.0, 10);
  track.poses[1].w() = nan;                // 0-1 and 1-2
  track.times[4] = track.times[3] - 0.02;  // 3-4 backwards; 4-5 is 0.1 m in 0.42 s: moving
  track.times[8] = nan;                    // 7-8 and 8-9
  p = track.profile();
  EXPECT_EQ(p.samples, 5u);
  EXPECT_NEAR(p.moving_s, 0.42, kTol);
  EXPECT_NEAR(p.cruise_s, 4 * kDt, kTol);
  EXPECT_NEAR(p.total_yaw_rad, 0.0, kTol);

  // Mismatched sizes: only the common prefix (here 5 samples, 4 intervals).
  track = Track().add({kSpeed, 0, 0}, 0.0, 10);
  track.times.resize(5);
  p = track.profile();
  EXPECT_EQ(p.samples, 4u);
  EXPECT_NEAR(p.cruise_s, 0.8, kTol);
  track = Track().add({kSpeed, 0, 0}, 0.0, 10);
  track.poses.resize(3);
  EXPECT_NEAR(track.profile().flight_s, 0.4, kTol);
}

}  // namespace
