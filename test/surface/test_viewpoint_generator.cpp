#include "surface_nbv/surface/viewpoint_generator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "surface_nbv/surface/ise_extractor.h"
#include "surface_test_maps.h"

using namespace surface_nbv;
using namespace surface_nbv::test;

namespace {

constexpr double kDeg = M_PI / 180.0;

void expectVectorNear(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected) {
  EXPECT_NEAR((actual - expected).norm(), 0.0, 1e-12) << actual.transpose() << " vs " << expected.transpose();
}

// A 15 x 15 x 7.5 m world, known free for x < 10 m; a wall at x = 10 m
// (voxel 40) for 5 <= y < 10 m; unknown behind (x >= 10 m) elsewhere. Its
// ISEs are the two vertical edges of the wall: (39, 19, z) and (39, 40, z).
struct WallScene {
  TsdfMap map{gridConfig(Eigen::Vector3i(60, 60, 30))};
  std::unique_ptr<CollisionMap> collision;
  IseExtractor extractor;
  WallScene() {
    fillBox(&map, Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(40, 60, 30), VoxelState::kFree);
    fillBox(&map, Eigen::Vector3i(40, 20, 0), Eigen::Vector3i(41, 40, 30), VoxelState::kOccupied);
  }
  void refresh() {
    collision = collisionFor(map);
    extractor.update(map);
  }
};

}  // namespace

TEST(ViewpointGenerator, DirectionOnAFaceIsItsNormal) {
  TsdfMap map(gridConfig(Eigen::Vector3i(16, 16, 16)));
  fillAll(&map, VoxelState::kFree);
  fillBox(&map, Eigen::Vector3i(8, 0, 0), Eigen::Vector3i(16, 16, 16), VoxelState::kOccupied);
  const ViewpointGenerator generator(testSurfaceConfig());
  expectVectorNear(generator.direction(gridOf(map), Eigen::Vector3i(7, 3, 8)), -Eigen::Vector3d::UnitX());
}

TEST(ViewpointGenerator, DirectionAtAConvexEdgePointsAwayFromTheEdgeNotAlongAFaceNormal) {
  TsdfMap map(gridConfig(Eigen::Vector3i(16, 16, 16)));
  fillAll(&map, VoxelState::kFree);
  fillBox(&map, Eigen::Vector3i(8, 8, 0), Eigen::Vector3i(16, 16, 16), VoxelState::kOccupied);
  const ViewpointGenerator generator(testSurfaceConfig());
  const Eigen::Vector3d n = generator.direction(gridOf(map), Eigen::Vector3i(7, 7, 8));
  expectVectorNear(n, Eigen::Vector3d(-1, -1, 0).normalized());
  // The faces' normals are -x and -y: n_v is 45 degrees off both.
  EXPECT_NEAR(n.dot(-Eigen::Vector3d::UnitX()), std::sqrt(0.5), 1e-12);
}

TEST(ViewpointGenerator, DirectionAtCorners) {
  const ViewpointGenerator generator(testSurfaceConfig());
  {  // Convex corner of a solid octant: along the diagonal, away from it.
    TsdfMap map(gridConfig(Eigen::Vector3i(16, 16, 16)));
    fillAll(&map, VoxelState::kFree);
    fillBox(&map, Eigen::Vector3i(8, 8, 8), Eigen::Vector3i(16, 16, 16), VoxelState::kOccupied);
    expectVectorNear(generator.direction(gridOf(map), Eigen::Vector3i(7, 7, 7)), -Eigen::Vector3d(1, 1, 1).normalized());
  }
  {  // Concave corner between a floor and a wall: the bisector, where a face normal is +x or +z.
    TsdfMap map(gridConfig(Eigen::Vector3i(16, 16, 16)));
    fillAll(&map, VoxelState::kFree);
    fillBox(&map, Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(16, 16, 4), VoxelState::kOccupied);
    fillBox(&map, Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(4, 16, 16), VoxelState::kOccupied);
    const Eigen::Vector3d n = generator.direction(gridOf(map), Eigen::Vector3i(4, 8, 4));
    expectVectorNear(n, Eigen::Vector3d(1, 0, 1).normalized());
    EXPECT_LT(n.z(), 0.75);
  }
  {  // Occupied on two opposite sides only: the sum vanishes, no direction.
    TsdfMap map(gridConfig(Eigen::Vector3i(16, 16, 16)));
    fillAll(&map, VoxelState::kFree);
    setState(&map, Eigen::Vector3i(6, 8, 8), VoxelState::kOccupied);
    setState(&map, Eigen::Vector3i(8, 8, 8), VoxelState::kOccupied);
    EXPECT_EQ(generator.direction(gridOf(map), Eigen::Vector3i(7, 8, 8)), Eigen::Vector3d::Zero());
  }
}

TEST(ViewpointGenerator, Eq2PoseSitsDeltaPoseAlongNvLookingAtTheIse) {
  WallScene scene;
  scene.refresh();
  ASSERT_EQ(scene.extractor.size(), 60u);
  const SurfaceConfig config = testSurfaceConfig();
  const ViewpointGenerator generator(config);
  const VoxelRayCaster rays(scene.extractor.states(), config.unknown_blocks_visibility);
  const Eigen::Vector3i v(39, 19, 15);
  ASSERT_TRUE(scene.extractor.isIse(v));
  const Eigen::Vector3d n = generator.direction(scene.extractor.states(), v);
  expectVectorNear(n, Eigen::Vector3d(-1, -1, 0).normalized());
  Viewpoint pose;
  const PoseSearch search = generator.generate(rays, *scene.collision, scene.map.config().bounds, v, n, &pose);
  ASSERT_TRUE(search.found);
  EXPECT_EQ(search.tested, 1);
  EXPECT_FALSE(search.unknown_blocked);
  const Eigen::Vector3d centre = scene.map.voxelCenter(v);
  EXPECT_NEAR((pose.position - centre).norm(), config.delta_pose, 1e-9);
  expectVectorNear((pose.position - centre) / config.delta_pose, n);
  EXPECT_NEAR(pose.yaw, 45.0 * kDeg, 1e-12);
  expectVectorNear(pose.view_direction, -n);
}

TEST(ViewpointGenerator, BlockedEq2PoseFallsBackToAShorterDistance) {
  WallScene scene;
  // An obstacle right where the eq. 2 pose of (39, 19, 15) would be.
  const Eigen::Vector3d centre = scene.map.voxelCenter(Eigen::Vector3i(39, 19, 15));
  Eigen::Vector3i blocked;
  ASSERT_TRUE(scene.map.voxelIndex(centre + 4.7 * Eigen::Vector3d(-1, -1, 0).normalized(), &blocked));
  setState(&scene.map, blocked, VoxelState::kOccupied);
  scene.refresh();
  SurfaceConfig config = testSurfaceConfig();
  config.fallback_distance_fractions = {0.5};
  const ViewpointGenerator generator(config);
  const VoxelRayCaster rays(scene.extractor.states(), true);
  const Eigen::Vector3i v(39, 19, 15);
  Viewpoint pose;
  const PoseSearch search = generator.generate(rays, *scene.collision, scene.map.config().bounds, v,
                                               generator.direction(scene.extractor.states(), v), &pose);
  ASSERT_TRUE(search.found);
  EXPECT_EQ(search.tested, 2);
  EXPECT_NEAR((pose.position - centre).norm(), 0.5 * config.delta_pose, 1e-9);
}

TEST(ViewpointGenerator, UnknownBlockedIseGetsAnApproachPoseBeyondTheUnknownBand) {
  WallScene scene;
  // Unknown space from 6 to 9 m in x: every pose up to delta_pose from the
  // wall's edge (39, 19, 15) at x = 9.9 m touches it with the 1 m radius.
  fillBox(&scene.map, Eigen::Vector3i(24, 0, 0), Eigen::Vector3i(36, 60, 30), VoxelState::kUnknown);
  scene.refresh();
  SurfaceConfig config = testSurfaceConfig();
  config.approach_range_fraction = 0.9;
  const ViewpointGenerator generator(config);
  const VoxelRayCaster rays(scene.extractor.states(), true);
  const VoxelRayCaster loose(scene.extractor.states(), false);
  const Eigen::Vector3i v(39, 19, 15);
  ASSERT_TRUE(scene.extractor.isIse(v));
  const Eigen::Vector3d n = generator.direction(scene.extractor.states(), v);
  const AlignedBox& bounds = scene.map.config().bounds;
  Viewpoint strict_pose;
  const PoseSearch strict = generator.generate(rays, *scene.collision, bounds, v, n, &strict_pose);
  EXPECT_FALSE(strict.found);
  EXPECT_TRUE(strict.unknown_blocked);
  EXPECT_FALSE(strict.approach);

  Viewpoint pose;
  const PoseSearch search = generator.generate(rays, *scene.collision, bounds, v, n, &pose, &loose);
  ASSERT_TRUE(search.found);
  EXPECT_TRUE(search.approach);
  EXPECT_GT(search.tested, strict.tested);
  const Eigen::Vector3d centre = scene.map.voxelCenter(v);
  const double d = (pose.position - centre).norm();
  EXPECT_GT(d, config.delta_pose - 1e-9);
  EXPECT_LE(d, config.approach_range_fraction * config.camera.max_range + 1e-9);
  // On the near side of the band, clear of it by the collision radius, and
  // looking at the ISE across it.
  EXPECT_LT(pose.position.x(), 6.0 - config.collision_radius);
  EXPECT_TRUE(scene.collision->isFree(pose.position, config.collision_radius));
  EXPECT_TRUE(bounds.contains(pose.position));
  expectVectorNear(pose.view_direction, (centre - pose.position).normalized());
  uint64_t steps = 0;
  EXPECT_FALSE(rays.clear(pose.position, v, &steps));
  EXPECT_TRUE(loose.clear(pose.position, v, &steps));

  // A zero approach range turns approach poses off, loose rays or not.
  config.approach_range_fraction = 0.0;
  const ViewpointGenerator no_approach(config);
  Viewpoint none;
  EXPECT_FALSE(no_approach.generate(rays, *scene.collision, bounds, v, n, &none, &loose).approach);
}

TEST(ViewpointGenerator, VerticalDirectionIsTiltedIntoTheVerticalFov) {
  WallScene scene;
  scene.refresh();
  const SurfaceConfig config = testSurfaceConfig();
  const ViewpointGenerator generator(config);
  const VoxelRayCaster rays(scene.extractor.states(), true);
  const Eigen::Vector3i v(12, 30, 8);
  const Eigen::Vector3d centre = scene.map.voxelCenter(v);
  const AlignedBox& bounds = scene.map.config().bounds;
  // Straight above, the ISE is outside the vertical FOV: not acceptable.
  EXPECT_FALSE(generator.acceptable(rays, *scene.collision, bounds, v, centre + 4.7 * Eigen::Vector3d::UnitZ()));
  Viewpoint pose;
  const PoseSearch search = generator.generate(rays, *scene.collision, bounds, v, Eigen::Vector3d::UnitZ(), &pose);
  ASSERT_TRUE(search.found);
  EXPECT_EQ(search.tested, 1);
  const Eigen::Vector3d d = centre - pose.position;
  EXPECT_NEAR(d.norm(), config.delta_pose, 1e-9);
  // Moved up to the usable edge of the FOV: 30 degrees less the 2 degree margin.
  EXPECT_NEAR(std::asin(d.z() / d.norm()), -28.0 * kDeg, 1e-9);
  EXPECT_NEAR(std::abs(pose.yaw), M_PI, 1e-9);  // first of the 8 yaws: the pose at +x looks along -x
  // Just outside the margin is refused, just inside accepted.
  auto at = [&](double elevation_deg) -> Eigen::Vector3d {
    return centre + 4.7 * Eigen::Vector3d(std::cos(elevation_deg * kDeg), 0, std::sin(elevation_deg * kDeg));
  };
  EXPECT_TRUE(generator.acceptable(rays, *scene.collision, bounds, v, at(27.9)));
  EXPECT_FALSE(generator.acceptable(rays, *scene.collision, bounds, v, at(28.1)));
}

// A mount pitched down moves the usable elevations down with the FOV: the
// pose may sit higher above its ISE and less far below it.
TEST(ViewpointGenerator, APitchedCameraShiftsTheUsableElevations) {
  WallScene scene;
  scene.refresh();
  SurfaceConfig config = testSurfaceConfig();
  config.camera.pitch_deg = 10.0;
  const ViewpointGenerator generator(config);
  const VoxelRayCaster rays(scene.extractor.states(), true);
  const Eigen::Vector3i v(12, 30, 15);
  const Eigen::Vector3d centre = scene.map.voxelCenter(v);
  const AlignedBox& bounds = scene.map.config().bounds;
  auto at = [&](double elevation_deg) -> Eigen::Vector3d {
    return centre + 3.0 * Eigen::Vector3d(std::cos(elevation_deg * kDeg), 0, std::sin(elevation_deg * kDeg));
  };
  // 30 + 10 - 2 degrees above, 30 - 10 - 2 below.
  EXPECT_TRUE(generator.acceptable(rays, *scene.collision, bounds, v, at(37.9)));
  EXPECT_FALSE(generator.acceptable(rays, *scene.collision, bounds, v, at(38.1)));
  EXPECT_TRUE(generator.acceptable(rays, *scene.collision, bounds, v, at(-17.9)));
  EXPECT_FALSE(generator.acceptable(rays, *scene.collision, bounds, v, at(-18.1)));
  // Straight up is tilted to the new upper edge.
  Viewpoint pose;
  ASSERT_TRUE(generator.generate(rays, *scene.collision, bounds, v, Eigen::Vector3d::UnitZ(), &pose).found);
  const Eigen::Vector3d d = pose.position - centre;
  EXPECT_NEAR(std::asin(d.z() / d.norm()), 38.0 * kDeg, 1e-9);
  // The ISE at a pose 38 degrees above lies inside the pitched camera's image.
  const DepthCamera camera(config.camera);
  EXPECT_TRUE(camera.sees(pose.cameraPose(config.camera).inverse() * centre));
  // The min range is along the pitched optical axis: 1.6 m of depth is at
  // 1.6 / cos(38 - 10 degrees) from the ISE.
  const double closest = config.camera.min_range / std::cos(28.0 * kDeg);
  EXPECT_TRUE(generator.acceptable(rays, *scene.collision, bounds, v,
                                   centre + (closest + 1e-6) * Eigen::Vector3d(std::cos(38 * kDeg), 0, std::sin(38 * kDeg))));
  EXPECT_FALSE(generator.acceptable(rays, *scene.collision, bounds, v,
                                    centre + (closest - 1e-3) * Eigen::Vector3d(std::cos(38 * kDeg), 0, std::sin(38 * kDeg))));
}

TEST(ViewpointGenerator, CandidateOrder) {
  SurfaceConfig config = testSurfaceConfig();
  config.fallback_rotations_deg = {30.0};
  config.fallback_distance_fractions = {0.75, 0.5};
  const ViewpointGenerator generator(config);
  const auto dirs = generator.candidateDirections(Eigen::Vector3d::UnitX());
  // n_v, yaw +30, yaw -30, elevation +28 (clamped from 30), elevation -28.
  ASSERT_EQ(dirs.size(), 5u);
  expectVectorNear(dirs[0], Eigen::Vector3d::UnitX());
  expectVectorNear(dirs[1], Eigen::Vector3d(std::cos(30 * kDeg), std::sin(30 * kDeg), 0));
  expectVectorNear(dirs[2], Eigen::Vector3d(std::cos(30 * kDeg), -std::sin(30 * kDeg), 0));
  expectVectorNear(dirs[3], Eigen::Vector3d(std::cos(28 * kDeg), 0, std::sin(28 * kDeg)));
  expectVectorNear(dirs[4], Eigen::Vector3d(std::cos(28 * kDeg), 0, -std::sin(28 * kDeg)));
  const auto distances = generator.candidateDistances(0.0);
  ASSERT_EQ(distances.size(), 4u);
  EXPECT_DOUBLE_EQ(distances[0], 4.7);
  EXPECT_DOUBLE_EQ(distances[1], 0.75 * 4.7);
  EXPECT_DOUBLE_EQ(distances[2], 0.5 * 4.7);
  EXPECT_NEAR(distances[3], 1.6, 1e-5);  // the camera's min range
  // A vertical n_v gets 8 yaws at the clamped elevation first.
  const auto vertical = generator.candidateDirections(Eigen::Vector3d::UnitZ());
  ASSERT_GE(vertical.size(), 8u);
  for (int k = 0; k < 8; ++k) EXPECT_NEAR(std::asin(vertical[k].z()), 28.0 * kDeg, 1e-12);
}
