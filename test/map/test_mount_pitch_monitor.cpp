// The mapper's check of the image frames' optical axis against camera/pitch_deg.
#include "surface_nbv/map/mount_pitch_monitor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "surface_nbv/sensor/camera_mount.h"

using namespace surface_nbv;

TEST(MountPitchMonitor, ReadsTheMountsPitchFromTheCameraPose) {
  CameraConfig camera;
  for (double pitch : {0.0, 5.73, -20.0}) {
    camera.pitch_deg = pitch;
    for (double yaw : {0.0, 1.0, -2.5}) {
      const Transform T_W_C = levelBodyPose(Eigen::Vector3d(1, 2, 3), yaw) * opticalInBody(camera);
      EXPECT_NEAR(MountPitchMonitor::axisPitchDeg(T_W_C), pitch, 1e-9) << yaw;
    }
  }
}

// A tilting UAV (up to 10 degrees either way with its accelerations) whose
// camera is mounted 5.73 degrees down: the mean finds the mount; a config
// that says level is a mismatch, one that says 5.73 (or 5) is not.
TEST(MountPitchMonitor, TheMeanOfATiltingFlightFindsTheMount) {
  CameraConfig camera;
  camera.pitch_deg = 5.73;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> tilt(-10.0, 10.0), yaw(-M_PI, M_PI);
  MountPitchMonitor monitor;
  EXPECT_TRUE(std::isnan(monitor.meanPitchDeg()));
  for (int i = 0; i < 600; ++i) {
    Transform T_W_B = levelBodyPose(Eigen::Vector3d::Zero(), yaw(rng));
    T_W_B.linear() = T_W_B.linear() * Eigen::AngleAxisd(tilt(rng) * M_PI / 180.0, Eigen::Vector3d::UnitY());
    monitor.add(T_W_B * opticalInBody(camera));
    if (i == 10) {
      EXPECT_FALSE(monitor.mismatch(0.0)) << "too few frames to tell";
    }
  }
  EXPECT_EQ(monitor.frames(), 600u);
  EXPECT_NEAR(monitor.meanPitchDeg(), 5.73, 1.0);
  EXPECT_TRUE(monitor.mismatch(0.0));
  EXPECT_FALSE(monitor.mismatch(5.73));
  EXPECT_FALSE(monitor.mismatch(5.0));
  // A pose that is not a rotation is not counted.
  Transform broken = Transform::Identity();
  broken.linear() *= std::nan("");
  monitor.add(broken);
  EXPECT_EQ(monitor.frames(), 600u);
}
