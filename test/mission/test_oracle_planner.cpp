// The oracle reference path on the built-in 4 m box (config/box.yaml): it
// covers the coverable surface, keeps its viewpoints and path clear of the
// true mesh, and repeats exactly with a seed. In the closed room
// (config/room.yaml) it keeps only the viewpoints the start reaches.
#include "surface_nbv/mission/oracle_planner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "surface_nbv/eval/free_space_grid.h"

using namespace surface_nbv;

namespace {

// Distance from p to the nearest triangle of the ground-truth mesh.
double meshDistance(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3i& t : mesh.triangles) {
    best = std::min(best, squaredDistanceToTriangle(p, mesh.vertices[t[0]].cast<double>(),
                                                    mesh.vertices[t[1]].cast<double>(),
                                                    mesh.vertices[t[2]].cast<double>()));
  }
  return std::sqrt(best);
}

class OracleOnBox : public ::testing::Test {
 protected:
  void SetUp() override {
    MissionConfig mission;
    ASSERT_TRUE(loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/box.yaml", &mission).ok());
    ASSERT_TRUE(loadScene(mission.scene, &mesh_).ok());
    ASSERT_TRUE(RaycastScene::create(mesh_, &scene_).ok());
    config_ = oracleConfigFrom(mission);
    config_.seed = 3;
  }

  TriangleMesh mesh_;
  std::unique_ptr<RaycastScene> scene_;
  OracleConfig config_;
};

TEST_F(OracleOnBox, CoversTheBoxWithCollisionFreeViewpointsAndPath) {
  OraclePlanner oracle(config_, mesh_, *scene_);
  const OracleResult r = oracle.plan();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  ASSERT_NE(oracle.collision(), nullptr);
  const double radius = config_.path.collision_radius;
  const double cell = oracle.collision()->cellSize();

  // Out of every candidate's sight: the face resting on the ground (z = 0,
  // a sixth of the area) and at most the foot of the sides, which only a
  // camera a few centimetres above its floor clearance (1.3 m) sees.
  EXPECT_GT(r.targets, 300u);
  EXPECT_EQ(r.coverable + r.uncoverable.size(), r.targets);
  EXPECT_GE(r.coverable, r.targets * 5 / 6 - r.targets / 50);
  for (const Eigen::Vector3d& p : r.uncoverable) EXPECT_LT(p.z(), 0.15) << p.transpose();
  EXPECT_GE(r.covered, static_cast<size_t>(std::ceil(0.99 * r.coverable)));
  EXPECT_LE(r.covered, r.coverable);

  // Every chosen viewpoint is clear in the perfect map and of the true mesh.
  ASSERT_FALSE(r.viewpoints.empty());
  EXPECT_GE(r.viewpoints.size(), 5u);  // five visible faces of a box need at least five views
  for (const Eigen::Vector4d& q : r.viewpoints) {
    EXPECT_TRUE(oracle.collision()->isFree(q.head<3>(), radius)) << q.transpose();
    EXPECT_GE(meshDistance(mesh_, q.head<3>()), radius) << q.transpose();
  }

  // The tour visits each chosen viewpoint once, from the start.
  ASSERT_EQ(r.order.size(), r.viewpoints.size());
  std::vector<int> visits(r.viewpoints.size(), 0);
  for (int k : r.order) ++visits.at(k);
  for (int v : visits) EXPECT_EQ(v, 1);
  EXPECT_EQ(r.failed_legs, 0u);
  ASSERT_EQ(r.path.size(), r.path_viewpoint.size());
  ASSERT_GE(r.path.size(), 2u);
  EXPECT_TRUE(r.path.front().isApprox(config_.start));
  EXPECT_TRUE(r.path.back().isApprox(r.viewpoints[r.order.back()]));

  // The path is collision-free: sampled every 5 cm along it, each point is
  // clear of the radius in the map and (up to the map's cell) of the true mesh.
  double length = 0.0;
  for (size_t i = 1; i < r.path.size(); ++i) {
    const Eigen::Vector3d a = r.path[i - 1].head<3>(), b = r.path[i].head<3>();
    length += (b - a).norm();
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.05)));
    for (int s = 0; s <= steps; ++s) {
      const Eigen::Vector3d p = a + (b - a) * (double(s) / steps);
      ASSERT_TRUE(oracle.collision()->isFree(p, radius)) << "segment " << i << " at " << p.transpose();
      ASSERT_GE(meshDistance(mesh_, p), radius - 0.6 * cell) << "segment " << i << " at " << p.transpose();
    }
  }
  EXPECT_NEAR(length, r.path_length, 1e-6);
  EXPECT_GE(r.path_length, r.tour_length - 1e-6);
  EXPECT_GT(r.tour_length, 0.0);
  EXPECT_GE(r.flight_time, r.path_length / config_.speed - 1e-6);
}

TEST_F(OracleOnBox, RepeatsExactlyWithTheSameSeed) {
  const OracleResult a = OraclePlanner(config_, mesh_, *scene_).plan();
  const OracleResult b = OraclePlanner(config_, mesh_, *scene_).plan();
  ASSERT_TRUE(a.status.ok()) << a.status.message();
  ASSERT_TRUE(b.status.ok()) << b.status.message();
  EXPECT_EQ(a.coverable, b.coverable);
  EXPECT_EQ(a.covered, b.covered);
  ASSERT_EQ(a.viewpoints.size(), b.viewpoints.size());
  for (size_t i = 0; i < a.viewpoints.size(); ++i) EXPECT_EQ(a.viewpoints[i], b.viewpoints[i]);
  EXPECT_EQ(a.order, b.order);
  ASSERT_EQ(a.path.size(), b.path.size());
  for (size_t i = 0; i < a.path.size(); ++i) EXPECT_EQ(a.path[i], b.path[i]);
  EXPECT_EQ(a.path_length, b.path_length);
  EXPECT_EQ(a.flight_time, b.flight_time);
}

TEST(OracleConfig, NamesTheBadKey) {
  OracleConfig c;
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
  c.cover_fraction = 1.5;
  EXPECT_NE(c.validate().message().find("cover_fraction"), std::string::npos);
  c = OracleConfig();
  c.offset_fractions = {1.0, -0.5};
  EXPECT_NE(c.validate().message().find("offset_fractions"), std::string::npos);
  c = OracleConfig();
  c.start = Eigen::Vector4d(100.0, 0.0, 2.0, 0.0);
  EXPECT_NE(c.validate().message().find("start"), std::string::npos);
}

TEST_F(OracleOnBox, PlanRefusesABadConfig) {
  config_.path_iterations = 0;
  const OracleResult r = OraclePlanner(config_, mesh_, *scene_).plan();
  EXPECT_FALSE(r.status.ok());
  EXPECT_NE(r.status.message().find("path_iterations"), std::string::npos) << r.status.message();
  EXPECT_TRUE(r.viewpoints.empty());
}

// The room (10 x 8 x 4 m, a pillar inside) in bounds reaching 3-4 m past
// its walls and 2 m over its ceiling: the candidates outside, in front of the
// walls' outer faces, are clear but not reachable from the start inside.
TEST(OracleInTheRoom, KeepsOnlyTheViewpointsInsideTheRoom) {
  MissionConfig mission;
  ASSERT_TRUE(loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/room.yaml", &mission).ok());
  TriangleMesh mesh;
  ASSERT_TRUE(loadScene(mission.scene, &mesh).ok());
  std::unique_ptr<RaycastScene> scene;
  ASSERT_TRUE(RaycastScene::create(mesh, &scene).ok());
  OracleConfig config = oracleConfigFrom(mission);
  config.seed = 1;
  OraclePlanner oracle(config, mesh, *scene);
  const OracleResult r = oracle.plan();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  EXPECT_GT(r.candidates, 0u);
  EXPECT_LT(r.candidates, r.candidates_built);
  ASSERT_FALSE(r.viewpoints.empty());
  for (const Eigen::Vector4d& q : r.viewpoints) {
    EXPECT_LT(std::abs(q.x()), 5.0) << q.transpose();
    EXPECT_LT(std::abs(q.y()), 4.0) << q.transpose();
    EXPECT_LT(q.z(), 4.0) << q.transpose();
  }
  for (const Eigen::Vector4d& p : r.path) {
    EXPECT_TRUE(std::abs(p.x()) < 5.0 && std::abs(p.y()) < 4.0 && p.z() < 4.0) << p.transpose();
  }
  EXPECT_GT(r.coveredFraction(), 0.9);

  // A start inside the pillar is refused, nothing flooded from it.
  config.start = Eigen::Vector4d(2.0, 1.0, 2.0, 0.0);
  const OracleResult pillar = OraclePlanner(config, mesh, *scene).plan();
  EXPECT_FALSE(pillar.status.ok());
  EXPECT_NE(pillar.status.message().find("start"), std::string::npos) << pillar.status.message();
  EXPECT_TRUE(pillar.viewpoints.empty());
}

}  // namespace
