#include "surface_nbv/sim/scripted_flight.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace surface_nbv;

namespace {

FlightConfig squareFlight() {
  FlightConfig c;
  c.target = AlignedBox(Eigen::Vector3d(-10, -5, 0), Eigen::Vector3d(10, 5, 8));
  c.standoff = 4.0;
  c.altitudes = {2.0, 6.0};
  c.speed = 0.5;
  return c;
}

double distanceToFootprint(const AlignedBox& box, const Eigen::Vector3d& p) {
  const double dx = std::max({box.min.x() - p.x(), 0.0, p.x() - box.max.x()});
  const double dy = std::max({box.min.y() - p.y(), 0.0, p.y() - box.max.y()});
  return std::hypot(dx, dy);
}

}  // namespace

TEST(ScriptedFlight, LengthIsLoopsPlusClimb) {
  const FlightConfig c = squareFlight();
  const ScriptedFlight flight(c);
  const double loop = 2 * (20.0 + 10.0) + 2 * M_PI * c.standoff;
  EXPECT_NEAR(flight.length(), 2 * loop + 4.0, 1e-9);
  EXPECT_NEAR(flight.duration(), flight.length() / 0.5, 1e-9);
}

TEST(ScriptedFlight, KeepsStandoffAndFacesTheBox) {
  const FlightConfig c = squareFlight();
  const ScriptedFlight flight(c);
  for (double s = 0.0; s <= flight.length(); s += 0.37) {
    const Transform T = flight.poseAtDistance(s);
    const Eigen::Vector3d p = T.translation();
    EXPECT_NEAR(distanceToFootprint(c.target, p), c.standoff, 1e-6) << "s = " << s;
    // Body x (forward) points at the nearest footprint point, horizontally.
    const Eigen::Vector3d nearest(std::clamp(p.x(), c.target.min.x(), c.target.max.x()),
                                  std::clamp(p.y(), c.target.min.y(), c.target.max.y()), p.z());
    const Eigen::Vector3d forward = T.linear().col(0);
    EXPECT_NEAR(forward.dot((nearest - p).normalized()), 1.0, 1e-6) << "s = " << s;
    EXPECT_NEAR(forward.z(), 0.0, 1e-12);
  }
}

TEST(ScriptedFlight, PathIsContinuous) {
  const ScriptedFlight flight(squareFlight());
  Eigen::Vector3d prev = flight.poseAtDistance(0.0).translation();
  for (double s = 0.05; s <= flight.length(); s += 0.05) {
    const Eigen::Vector3d p = flight.poseAtDistance(s).translation();
    EXPECT_LE((p - prev).norm(), 0.05 + 1e-9) << "jump at s = " << s;
    prev = p;
  }
}

TEST(ScriptedFlight, ClampsTimeAndFliesAltitudesInOrder) {
  const ScriptedFlight flight(squareFlight());
  EXPECT_NEAR(flight.poseAt(-5.0).translation().z(), 2.0, 1e-12);
  EXPECT_NEAR(flight.poseAt(1e9).translation().z(), 6.0, 1e-12);
  EXPECT_TRUE(flight.poseAt(1e9).translation().isApprox(flight.poseAt(flight.duration()).translation()));
}

TEST(ScriptedFlight, ValidateNamesBadFields) {
  FlightConfig c = squareFlight();
  c.speed = 0.0;
  EXPECT_NE(c.validate().message().find("speed"), std::string::npos);
  c = squareFlight();
  c.altitudes.clear();
  EXPECT_NE(c.validate().message().find("altitudes"), std::string::npos);
  c = squareFlight();
  c.standoff = NAN;
  EXPECT_NE(c.validate().message().find("standoff"), std::string::npos);
  c = squareFlight();
  c.target = AlignedBox();
  EXPECT_FALSE(c.validate().ok());
  EXPECT_TRUE(squareFlight().validate().ok());
}

TEST(ScriptedFlight, FlightAroundSpreadsLevelsOverHeight) {
  const AlignedBox box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 10, 15));
  const FlightConfig c = flightAround(box, 3.0, 3, 0.5);
  ASSERT_EQ(c.altitudes.size(), 3u);
  EXPECT_LT(c.altitudes[0], c.altitudes[1]);
  EXPECT_LT(c.altitudes[1], c.altitudes[2]);
  EXPECT_GT(c.altitudes[0], 1.5);
  EXPECT_LT(c.altitudes[2], 15.0);
}

TEST(OpticalInBody, LooksForwardWithImageDown) {
  const Transform T_B_C = opticalInBody(Eigen::Vector3d(0.1, 0.0, -0.05));
  EXPECT_TRUE((T_B_C.linear() * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_TRUE((T_B_C.linear() * Eigen::Vector3d::UnitY()).isApprox(-Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE((T_B_C.linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(T_B_C.linear().determinant(), 1.0, 1e-12);
  EXPECT_TRUE(T_B_C.translation().isApprox(Eigen::Vector3d(0.1, 0.0, -0.05)));
}

TEST(OpticalInBody, APitchedMountLooksDownByItsPitch) {
  CameraConfig camera;
  camera.pitch_deg = 5.73;  // RotorS's VI-sensor: 0.1 rad
  const Transform T_B_C = opticalInBody(camera);
  const double p = 5.73 * M_PI / 180.0;
  const Eigen::Vector3d forward = T_B_C.linear() * Eigen::Vector3d::UnitZ();
  EXPECT_TRUE(forward.isApprox(Eigen::Vector3d(std::cos(p), 0.0, -std::sin(p)))) << forward.transpose();
  EXPECT_TRUE((T_B_C.linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitY()));  // right stays level
  EXPECT_NEAR(T_B_C.linear().determinant(), 1.0, 1e-12);
  EXPECT_TRUE(T_B_C.translation().isZero());
  // Negative is up; zero is the level mount.
  EXPECT_GT((opticalInBody(Eigen::Vector3d::Zero(), -10.0).linear() * Eigen::Vector3d::UnitZ()).z(), 0.0);
  EXPECT_TRUE(opticalInBody(CameraConfig()).isApprox(opticalInBody()));
}
