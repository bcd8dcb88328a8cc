// Gaze while flying (gaze_yaw.h): which ISEs the camera sees, the
// yaws a leg gets, and the explorer's use of them.
#include "surface_nbv/planning/gaze_yaw.h"

#include <cmath>

#include <gtest/gtest.h>

#include "planning_test_worlds.h"
#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/sensor/camera_mount.h"
#include "surface_nbv/util/angles.h"

using namespace surface_nbv;

namespace {

// A row of targets at x = `x`, y in [y0, y1] every metre, height z, facing `direction`.
std::vector<GazeTarget> row(double x, double y0, double y1, double z, const Eigen::Vector3d& direction) {
  std::vector<GazeTarget> out;
  for (double y = y0; y <= y1 + 1e-9; y += 1.0) out.push_back({Eigen::Vector3d(x, y, z), direction});
  return out;
}

// A straight leg along +y at x = 0 (yaw pi/2 everywhere, as travel_yaw sets it).
std::vector<Eigen::Vector4d> straightLeg(double y0, double y1, double z) {
  return {Eigen::Vector4d(0.0, y0, z, M_PI / 2), Eigen::Vector4d(0.0, y1, z, M_PI / 2)};
}

double yawAt(const std::vector<Eigen::Vector4d>& path, double y) {
  size_t best = 0;
  for (size_t i = 0; i < path.size(); ++i)
    if (std::abs(path[i].y() - y) < std::abs(path[best].y() - y)) best = i;
  return path[best].w();
}

TEST(GazeYaw, CountsOnlyTargetsInsideTheFrustumAndRange) {
  GazeConfig c;  // 90 x 60 deg, [1.6, 8] m
  const Eigen::Vector3d facing(-1, 0, 0);
  const Eigen::Vector3d p(0, 0, 2);
  auto at = [&](double x, double y, double z) { return std::vector<GazeTarget>{{Eigen::Vector3d(x, y, z), facing}}; };
  EXPECT_EQ(countVisible(c, at(5, 0, 2), nullptr, p, 0.0), 1);
  EXPECT_EQ(countVisible(c, at(1, 0, 2), nullptr, p, 0.0), 0) << "closer than min_range";
  EXPECT_EQ(countVisible(c, at(9, 0, 2), nullptr, p, 0.0), 0) << "beyond max_range";
  EXPECT_EQ(countVisible(c, at(5, 4, 2), nullptr, p, 0.0), 1) << "38.7 deg off axis, inside 45";
  EXPECT_EQ(countVisible(c, at(5, 6, 2), nullptr, p, 0.0), 0) << "50.2 deg off axis";
  EXPECT_EQ(countVisible(c, at(5, 0, 4.5), nullptr, p, 0.0), 1) << "26.6 deg up, inside 30";
  EXPECT_EQ(countVisible(c, at(5, 0, 5.5), nullptr, p, 0.0), 0) << "35 deg up";
  EXPECT_EQ(countVisible(c, at(5, 0, 2), nullptr, p, M_PI), 0) << "behind the camera";
  EXPECT_EQ(countVisible(c, at(0, 5, 2), nullptr, p, M_PI / 2), 0) << "its direction faces +x, away from p";
  const std::vector<GazeTarget> away{{Eigen::Vector3d(5, 0, 2), Eigen::Vector3d(1, 0, 0)}};
  EXPECT_EQ(countVisible(c, away, nullptr, p, 0.0), 0) << "p is behind the surface";
}

// The frustum of a mount pitched down 10 degrees, against the camera model
// through the mount's transform.
TEST(GazeYaw, APitchedCameraCountsWhatItsImageHolds) {
  GazeConfig c;
  c.camera.pitch_deg = 10.0;
  const DepthCamera camera(c.camera);
  const Eigen::Vector3d p(0, 0, 20);
  const Transform T_C_W = (levelBodyPose(p, 0.0) * opticalInBody(c.camera)).inverse();
  int seen = 0;
  for (double x = 1.0; x <= 9.0; x += 0.5) {
    for (double y = -7.0; y <= 7.0; y += 0.5) {
      for (double z = 13.0; z <= 25.0; z += 0.5) {
        const Eigen::Vector3d t(x, y, z);
        const Eigen::Vector3d p_C = T_C_W * t;
        const bool edge = std::abs(std::abs(p_C.x() / p_C.z()) - 1.0) < 1e-9 ||
                          std::abs(std::abs(p_C.y() / p_C.z()) - std::tan(M_PI / 6)) < 1e-9;
        if (edge) continue;
        const std::vector<GazeTarget> one{{t, (p - t).normalized()}};
        const bool expected = camera.sees(p_C);
        ASSERT_EQ(countVisible(c, one, nullptr, p, 0.0), expected ? 1 : 0) << t.transpose();
        seen += expected;
      }
    }
  }
  EXPECT_GT(seen, 1000);
  // 35 degrees down: outside the level camera's FOV, inside the pitched one's.
  const std::vector<GazeTarget> low{{Eigen::Vector3d(5, 0, 20 - 5 * std::tan(35 * M_PI / 180)), Eigen::Vector3d(-1, 0, 0)}};
  EXPECT_EQ(countVisible(c, low, nullptr, p, 0.0), 1);
  EXPECT_EQ(countVisible(GazeConfig(), low, nullptr, p, 0.0), 0);
}

TEST(GazeYaw, LegLooksAtTheTargetsItPasses) {
  GazeConfig c;
  const std::vector<GazeTarget> targets = row(4.0, -5.0, 5.0, 2.0, Eigen::Vector3d(-1, 0, 0));
  std::vector<Eigen::Vector4d> path = straightLeg(-20.0, 20.0, 2.0);
  const int set = applyGaze(c, targets, nullptr, 4.0, &path);
  EXPECT_GT(set, 3);
  // Resampled every step up to the kept end (2, 4, ..., 34 m), the geometry
  // kept, the ends untouched.
  ASSERT_EQ(path.size(), 19u);
  EXPECT_TRUE(path.front().isApprox(Eigen::Vector4d(0, -20, 2, M_PI / 2)));
  EXPECT_TRUE(path.back().isApprox(Eigen::Vector4d(0, 20, 2, M_PI / 2)));
  for (size_t i = 1; i < path.size(); ++i) {
    EXPECT_NEAR(path[i].x(), 0.0, 1e-9);
    EXPECT_GT(path[i].y(), path[i - 1].y());
    if (i + 1 < path.size()) {
      EXPECT_NEAR(path[i].y() - path[i - 1].y(), c.step, 1e-9);
    }
  }
  // Beside the row it looks at it (+x); far from it, along the leg.
  EXPECT_LT(std::abs(wrapAngle(yawAt(path, 0.0))), 0.5) << yawAt(path, 0.0);
  EXPECT_NEAR(yawAt(path, -16.0), M_PI / 2, 1e-9);
  EXPECT_NEAR(yawAt(path, 14.0), M_PI / 2, 1e-9);
  // The last keep_end metres keep their yaw.
  for (const Eigen::Vector4d& q : path) {
    if (q.y() > 16.0) {
      EXPECT_NEAR(q.w(), M_PI / 2, 1e-9);
    }
  }
  // Every gaze yaw sees at least min_ises, and no fewer than along the leg.
  for (const Eigen::Vector4d& q : path) {
    const int n = countVisible(c, targets, nullptr, q.head<3>(), q.w());
    if (std::abs(wrapAngle(q.w() - M_PI / 2)) > 1e-9) {
      EXPECT_GE(n, c.min_ises);
      EXPECT_GE(n, countVisible(c, targets, nullptr, q.head<3>(), M_PI / 2));
    }
  }
}

TEST(GazeYaw, KeepsTheHeadingWithoutEnoughVisibleTargets) {
  GazeConfig c;
  c.min_ises = 3;
  std::vector<Eigen::Vector4d> path = straightLeg(-10.0, 10.0, 2.0);
  // Facing away from the leg: not visible from it.
  EXPECT_EQ(applyGaze(c, row(4.0, -5.0, 5.0, 2.0, Eigen::Vector3d(1, 0, 0)), nullptr, 2.0, &path), 0);
  for (const Eigen::Vector4d& q : path) EXPECT_NEAR(q.w(), M_PI / 2, 1e-9);
  // Two targets are fewer than min_ises.
  path = straightLeg(-10.0, 10.0, 2.0);
  EXPECT_EQ(applyGaze(c, row(4.0, 0.0, 1.0, 2.0, Eigen::Vector3d(-1, 0, 0)), nullptr, 2.0, &path), 0);
  // A leg shorter than a step plus its kept end is left alone.
  path = straightLeg(0.0, 3.0, 2.0);
  EXPECT_EQ(applyGaze(c, row(4.0, -5.0, 5.0, 2.0, Eigen::Vector3d(-1, 0, 0)), nullptr, 2.0, &path), 0);
  EXPECT_EQ(path.size(), 2u);
  // No targets.
  path = straightLeg(-10.0, 10.0, 2.0);
  EXPECT_EQ(applyGaze(c, {}, nullptr, 2.0, &path), 0);
  EXPECT_EQ(path.size(), 2u);
}

TEST(GazeYaw, WallsAndUnknownSpaceBlockTheView) {
  // WallWorld: an occupied wall at |x| < 0.25 across the whole map.
  WallWorld world(false);
  GazeConfig c;
  c.min_ises = 1;
  const Eigen::Vector3d p(-3.0, 0.0, 2.5);
  const std::vector<GazeTarget> behind = row(1.5, -1.0, 1.0, 2.5, Eigen::Vector3d(-1, 0, 0));
  const std::vector<GazeTarget> before = row(-0.9, -1.0, 1.0, 2.5, Eigen::Vector3d(-1, 0, 0));
  EXPECT_EQ(countVisible(c, behind, nullptr, p, 0.0), 3) << "without a map nothing blocks";
  EXPECT_EQ(countVisible(c, behind, &world.collision(), p, 0.0), 0);
  EXPECT_EQ(countVisible(c, before, &world.collision(), p, 0.0), 3);
  // Outside the map's bounds everything is an obstacle.
  const std::vector<GazeTarget> outside{{Eigen::Vector3d(-3.0, 0.0, 5.5), Eigen::Vector3d(0, -1, 0)}};
  EXPECT_EQ(countVisible(c, outside, nullptr, Eigen::Vector3d(-3.0, -5.0, 4.5), M_PI / 2), 1);
  EXPECT_EQ(countVisible(c, outside, &world.collision(), Eigen::Vector3d(-3.0, -5.0, 4.5), M_PI / 2), 0);

  std::vector<Eigen::Vector4d> path{Eigen::Vector4d(-3.0, -5.0, 2.5, M_PI / 2), Eigen::Vector4d(-3.0, 5.0, 2.5, M_PI / 2)};
  std::vector<Eigen::Vector4d> copy = path;
  EXPECT_EQ(applyGaze(c, behind, &world.collision(), 1.0, &copy), 0);
  EXPECT_GT(applyGaze(c, before, &world.collision(), 1.0, &path), 0);
}

TEST(GazeYaw, ConfigRefusesBadValues) {
  EXPECT_TRUE(GazeConfig().validate().ok());
  auto bad = [](auto change) {
    GazeConfig c;
    change(&c);
    return !c.validate().ok();
  };
  EXPECT_TRUE(bad([](GazeConfig* c) { c->step = 0.0; }));
  EXPECT_TRUE(bad([](GazeConfig* c) { c->step = std::nan(""); }));
  EXPECT_TRUE(bad([](GazeConfig* c) { c->min_ises = 0; }));
  EXPECT_TRUE(bad([](GazeConfig* c) { c->yaw_bins = 2; }));
  EXPECT_TRUE(bad([](GazeConfig* c) { c->end_margin = -1.0; }));
  EXPECT_TRUE(bad([](GazeConfig* c) { c->camera.hfov_deg = 180.0; }));
  EXPECT_TRUE(bad([](GazeConfig* c) { c->camera.max_range = c->camera.min_range; }));
  ExplorerConfig e;
  e.travel_yaw = true;
  e.gaze.enabled = true;
  EXPECT_TRUE(e.validate().ok());
  e.travel_yaw = false;
  EXPECT_NE(e.validate().message().find("travel_yaw"), std::string::npos);
  e.travel_yaw = true;
  e.gaze.yaw_bins = 1;
  EXPECT_FALSE(e.validate().ok());
  e.gaze.enabled = false;
  EXPECT_TRUE(e.validate().ok()) << "a disabled gaze is not checked";
}

TEST(GazeYaw, ExplorerLegsLookAtTheFrontiersIses) {
  WallWorld world(true);
  ExplorerConfig config;
  config.travel_yaw = true;
  config.turn_distance = 1.0;
  config.gaze.enabled = true;
  config.gaze.min_ises = 2;
  PathPlannerConfig path = seededPlannerConfig(3, 2000, 10.0);
  Explorer explorer(config, path);
  ASSERT_TRUE(explorer.setMap(&world.collision(), world.bounds()).ok());
  // One viewpoint at the far end of the west side; ISEs on the west face of
  // the wall beside the way there, facing west.
  Frontier f;
  Viewpoint v;
  v.position = Eigen::Vector3d(-4.0, 4.5, 2.5);
  v.yaw = M_PI / 2;
  v.cluster = 0;
  for (double y = -3.0; y <= 3.0; y += 0.5) {
    Ise ise;
    ise.position = Eigen::Vector3d(-0.5, y, 2.5);
    ise.direction = Eigen::Vector3d(-1, 0, 0);
    ise.viewpoint = 0;
    v.visible.push_back(static_cast<uint32_t>(f.ises.size()));
    f.ises.push_back(ise);
  }
  f.viewpoints.push_back(v);
  Cluster cl;
  cl.viewpoints = {0};
  cl.visible_ises = f.ises.size();
  cl.gain = 1.0;
  f.clusters.push_back(cl);
  const ExplorerDecision d = explorer.update(f, Eigen::Vector4d(-4.0, -4.5, 2.5, M_PI / 2), false);
  ASSERT_EQ(d.action, ExplorerAction::kFly) << d.message;
  EXPECT_GT(explorer.stats().gaze_vertices, 0u);
  // Some vertex on the way looks east, at the wall's ISEs.
  bool east = false;
  for (const Eigen::Vector4d& q : d.path) east = east || std::abs(wrapAngle(q.w())) < 0.6;
  EXPECT_TRUE(east);
  EXPECT_NEAR(d.path.back().w(), M_PI / 2, 1e-9) << "the leg still ends at the target's yaw";

  // The same leg without gaze looks along the leg.
  config.gaze.enabled = false;
  Explorer plain(config, path);
  ASSERT_TRUE(plain.setMap(&world.collision(), world.bounds()).ok());
  const ExplorerDecision e = plain.update(f, Eigen::Vector4d(-4.0, -4.5, 2.5, M_PI / 2), false);
  ASSERT_EQ(e.action, ExplorerAction::kFly) << e.message;
  EXPECT_EQ(plain.stats().gaze_vertices, 0u);
  for (const Eigen::Vector4d& q : e.path) EXPECT_GT(std::abs(wrapAngle(q.w())), 0.6);
}

}  // namespace
