// The ground-truth gain of nbv_mission --oracle-gain on the built-in 4 m box
// (config/box.yaml): it counts the unobserved surface points a pose sees,
// not the ones behind the box or outside the view, and forgets the points a
// fused frame observed.
#include "surface_nbv/mission/oracle_gain.h"

#include <gtest/gtest.h>

#include <cmath>

#include "surface_nbv/map/tsdf_integrator.h"
#include "surface_nbv/mission/mission_config.h"
#include "surface_nbv/sensor/camera_mount.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/scene_source.h"

using namespace surface_nbv;

namespace {

// Points 0.2 m apart on the box's faces x = -2 (front, seen from -x) and
// x = +2 (back), for y and z inside the face.
std::vector<Eigen::Vector3d> facePoints(double x) {
  std::vector<Eigen::Vector3d> points;
  for (double y = -1.5; y <= 1.5 + 1e-9; y += 0.2)
    for (double z = 1.0; z <= 3.0 + 1e-9; z += 0.2) points.emplace_back(x, y, z);
  return points;
}

class OracleGainOnBox : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/box.yaml", &mission_).ok());
    TriangleMesh mesh;
    ASSERT_TRUE(loadScene(mission_.scene, &mesh).ok());
    ASSERT_TRUE(RaycastScene::create(mesh, &scene_).ok());
    front_ = facePoints(-2.0);
    std::vector<Eigen::Vector3d> points = front_;
    for (const Eigen::Vector3d& p : facePoints(2.0)) points.push_back(p);
    gain_ = std::make_unique<OracleGain>(*scene_, mission_.camera, points);
  }

  MissionConfig mission_;
  std::unique_ptr<RaycastScene> scene_;
  std::vector<Eigen::Vector3d> front_;
  std::unique_ptr<OracleGain> gain_;
};

TEST_F(OracleGainOnBox, CountsTheUnobservedPointsInViewAndNotBehindTheBox) {
  // 4 m in front of the face x = -2, looking along +x: the front face's 16 x 11
  // points are inside the 90 x 60 degree view, the back face is hidden.
  const Eigen::Vector4d facing(-6.0, 0.0, 2.0, 0.0);
  EXPECT_EQ((*gain_)(facing), static_cast<double>(front_.size()));
  // The same place looking away, and a pose beyond the camera's range.
  EXPECT_EQ((*gain_)(Eigen::Vector4d(-6.0, 0.0, 2.0, M_PI)), 0.0);
  EXPECT_EQ((*gain_)(Eigen::Vector4d(-2.5 - mission_.camera.max_range, 0.0, 2.0, 0.0)), 0.0);
  // Turned by 60 degrees the face leaves the 45 degree half-width only in part.
  const double turned = (*gain_)(Eigen::Vector4d(-6.0, 0.0, 2.0, M_PI / 3.0));
  EXPECT_GT(turned, 0.0);
  EXPECT_LT(turned, static_cast<double>(front_.size()));
}

TEST_F(OracleGainOnBox, ForgetsWhatAFusedFrameObserved) {
  TsdfMap map(mission_.tsdf);
  TsdfIntegrator integrator(&map);
  const DepthCamera camera(mission_.camera);
  const DepthRenderer renderer(*scene_, camera);
  const Eigen::Vector4d facing(-5.0, 0.0, 2.0, 0.0);
  gain_->update(map);
  EXPECT_EQ(gain_->unobserved(), 2 * front_.size());
  const Transform T_W_C = levelBodyPose(facing.head<3>(), facing.w()) * opticalInBody();
  DepthImage depth;
  renderer.render(T_W_C, &depth);
  for (int k = 0; k < 5; ++k) ASSERT_TRUE(integrator.integrateDepth(camera, depth, T_W_C).ok());
  for (const Eigen::Vector3d& p : front_) EXPECT_TRUE(surfaceObserved(map, p)) << p.transpose();
  EXPECT_FALSE(surfaceObserved(map, Eigen::Vector3d(2.0, 0.0, 2.0)));
  gain_->update(map);
  EXPECT_EQ(gain_->unobserved(), front_.size());  // the back face is left
  EXPECT_EQ((*gain_)(facing), 0.0);
}

}  // namespace
