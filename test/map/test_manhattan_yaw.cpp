// The heading from the walls (manhattan_yaw.h): the room's walls give their
// direction modulo 90 degrees from any view, a drifted heading shows as that
// direction turned, and the correction pulls it back.
#include "surface_nbv/map/manhattan_yaw.h"

#include <gtest/gtest.h>

#include <memory>

#include "surface_nbv/sensor/camera_mount.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/procedural_scenes.h"
#include "surface_nbv/sim/raycast_scene.h"

namespace surface_nbv {
namespace {

struct Room {
  std::unique_ptr<RaycastScene> scene;
  CameraConfig camera;
  Room() {
    TriangleMesh mesh;
    EXPECT_TRUE(makeProceduralScene("room", &mesh).ok());
    EXPECT_TRUE(RaycastScene::create(mesh, &scene).ok());
  }
  Transform pose(double yaw) const { return levelBodyPose(Eigen::Vector3d(-1.5, 1.0, 2.0), yaw) * opticalInBody(camera); }
  DepthImage render(const Transform& T, uint64_t frame = 0) const {
    DepthImage d;
    DepthRenderer(*scene, DepthCamera(camera), 2).render(T, &d, frame);
    return d;
  }
};

Transform turned(const Transform& T, double yaw) {
  Transform A = Transform::Identity();
  A.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  A.translation() = T.translation() - A.linear() * T.translation();
  return A * T;
}

TEST(ManhattanYaw, TheRoomsWallsLieAlongTheAxesFromEveryView) {
  Room room;
  const ManhattanYawConfig config;
  for (double yaw : {0.0, 0.7, 2.0, 3.5, 5.0}) {
    const Transform T = room.pose(yaw);
    const ManhattanYawFrame f = manhattanDirection(DepthCamera(room.camera), room.render(T), T, config);
    ASSERT_TRUE(f.trusted) << yaw << ": " << f.normals << " normals, concentration " << f.concentration;
    EXPECT_NEAR(f.direction, 0.0, 0.2 * M_PI / 180.0) << yaw;
    // Seen with a heading 3 degrees off, the walls turn by 3 degrees.
    const Transform off = turned(T, 3.0 * M_PI / 180.0);
    const ManhattanYawFrame g = manhattanDirection(DepthCamera(room.camera), room.render(T), off, config);
    EXPECT_NEAR(g.direction, 3.0 * M_PI / 180.0, 0.2 * M_PI / 180.0) << yaw;
  }
}

TEST(ManhattanYaw, NoisyStereoStillGivesTheDirection) {
  Room room;
  room.camera.noise_k = 0.007;
  room.camera.sensor.lateral_noise_px = 0.5;
  room.camera.sensor.dropout_rate = 0.01;
  const Transform T = room.pose(2.0);
  const ManhattanYawFrame f = manhattanDirection(DepthCamera(room.camera), room.render(T, 3), T, ManhattanYawConfig());
  ASSERT_TRUE(f.trusted) << f.normals << " normals, concentration " << f.concentration;
  EXPECT_NEAR(f.direction, 0.0, 1.0 * M_PI / 180.0);
}

TEST(ManhattanYaw, CorrectsAShareOfTheErrorAgainstTheFirstFrame) {
  Room room;
  ManhattanYawConfig config;
  config.gain = 0.1;
  ManhattanYaw yaw(config);
  const DepthCamera camera(room.camera);
  const Transform T = room.pose(0.5);
  const DepthImage depth = room.render(T);
  EXPECT_DOUBLE_EQ(yaw.update(camera, depth, T), 0.0);  // the first trusted frame is the reference
  ASSERT_TRUE(yaw.hasReference());
  const double error = 2.0 * M_PI / 180.0;
  EXPECT_NEAR(yaw.update(camera, depth, turned(T, error)), -0.1 * error, 0.03 * error);
  // An error past max_error_deg is another structure's direction, not drift.
  EXPECT_DOUBLE_EQ(yaw.update(camera, depth, turned(T, 20.0 * M_PI / 180.0)), 0.0);
  EXPECT_EQ(yaw.corrections(), 1u);
}

TEST(ManhattanYaw, BadFieldsAreNamed) {
  ManhattanYawConfig c;
  EXPECT_TRUE(c.validate().ok());
  c.gain = 0.0;
  EXPECT_EQ(c.validate().message().rfind("manhattan_yaw_gain", 0), 0u);
}

}  // namespace
}  // namespace surface_nbv
