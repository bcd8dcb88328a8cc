#include "surface_nbv/surface/visibility_evaluator.h"

#include <gtest/gtest.h>

#include <random>

#include "surface_nbv/sensor/depth_camera.h"
#include "surface_test_maps.h"

using namespace surface_nbv;
using namespace surface_nbv::test;

namespace {

Ise iseAt(const TsdfMap& map, const Eigen::Vector3i& v) {
  Ise ise;
  ise.voxel = v;
  ise.position = map.voxelCenter(v);
  return ise;
}

// 12 x 6 x 4 m, known free; a camera at (1, 3, 2) looking along +x.
struct Corridor {
  TsdfMap map{gridConfig(Eigen::Vector3i(48, 24, 16))};
  Viewpoint viewpoint;
  std::vector<Ise> ises;
  Corridor() {
    fillAll(&map, VoxelState::kFree);
    viewpoint.position = Eigen::Vector3d(1.0, 3.0, 2.0);
    viewpoint.yaw = 0.0;
    ises = {iseAt(map, Eigen::Vector3i(16, 12, 8)),   // 3.125 m ahead
            iseAt(map, Eigen::Vector3i(28, 12, 8)),   // 6.125 m ahead
            iseAt(map, Eigen::Vector3i(2, 12, 8)),    // behind the camera
            iseAt(map, Eigen::Vector3i(8, 12, 8)),    // 1.125 m ahead: under the min range
            iseAt(map, Eigen::Vector3i(40, 12, 8)),   // 9.125 m ahead: beyond the max range
            iseAt(map, Eigen::Vector3i(12, 23, 8)),   // 2.875 m to the side at 2.125 m: outside the 90 deg FOV
            iseAt(map, Eigen::Vector3i(28, 12, 15))}; // 1.875 m up at 6.125 m: inside the 60 deg FOV
  }
  std::vector<uint32_t> visible(const SurfaceConfig& config) {
    const VoxelStateGrid grid = gridOf(map);
    const VoxelRayCaster rays(grid, config.unknown_blocks_visibility);
    std::vector<Viewpoint> viewpoints{viewpoint};
    VisibilityEvaluator(config).evaluate(rays, ises, &viewpoints);
    return viewpoints[0].visible;
  }
};

}  // namespace

TEST(VisibilityEvaluator, FrustumAndRange) {
  Corridor corridor;
  EXPECT_EQ(corridor.visible(testSurfaceConfig()), (std::vector<uint32_t>{0, 1, 6}));
}

TEST(VisibilityEvaluator, AWallBetweenViewpointAndIseHidesIt) {
  Corridor corridor;
  fillBox(&corridor.map, Eigen::Vector3i(20, 0, 0), Eigen::Vector3i(21, 24, 16), VoxelState::kOccupied);
  SurfaceConfig config = testSurfaceConfig();
  EXPECT_EQ(corridor.visible(config), (std::vector<uint32_t>{0}));
  config.unknown_blocks_visibility = false;
  EXPECT_EQ(corridor.visible(config), (std::vector<uint32_t>{0}));
}

TEST(VisibilityEvaluator, UnknownSpaceHidesOnlyWhenConfigured) {
  Corridor corridor;
  fillBox(&corridor.map, Eigen::Vector3i(20, 0, 0), Eigen::Vector3i(21, 24, 16), VoxelState::kUnknown);
  SurfaceConfig config = testSurfaceConfig();
  ASSERT_TRUE(config.unknown_blocks_visibility);  // the default
  EXPECT_EQ(corridor.visible(config), (std::vector<uint32_t>{0}));
  config.unknown_blocks_visibility = false;
  EXPECT_EQ(corridor.visible(config), (std::vector<uint32_t>{0, 1, 6}));
}

// The evaluator's frustum against the camera model through the mount's
// transform, level and pitched (RotorS's 0.1 rad down, and 20 degrees up).
TEST(VisibilityEvaluator, FrustumAgreesWithTheCameraModel) {
  for (double pitch_deg : {0.0, 5.73, -20.0}) {
    SurfaceConfig config = testSurfaceConfig();
    config.camera.pitch_deg = pitch_deg;
    const VisibilityEvaluator evaluator(config);
    const DepthCamera camera(config.camera);
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> u(-10.0, 10.0), yaw(-M_PI, M_PI);
    int inside = 0, below_level = 0;
    for (int i = 0; i < 20000; ++i) {
      Viewpoint q;
      q.position = Eigen::Vector3d(u(rng), u(rng), u(rng));
      q.yaw = yaw(rng);
      const Eigen::Vector3d p = q.position + Eigen::Vector3d(u(rng), u(rng), 0.5 * u(rng));
      const Eigen::Vector3d p_C = q.cameraPose(config.camera).inverse() * p;
      const bool expected = camera.sees(p_C);
      // Points within 1e-9 of a frustum face may go either way.
      const bool edge = std::abs(std::abs(p_C.x() / p_C.z()) - 1.0) < 1e-9 ||
                        std::abs(std::abs(p_C.y() / p_C.z()) - std::tan(M_PI / 6)) < 1e-9;
      if (!edge) {
        ASSERT_EQ(evaluator.inFrustum(q, p), expected) << "pitch " << pitch_deg << ": " << p_C.transpose();
      }
      inside += expected ? 1 : 0;
      // Seen below the level camera's lower edge (30 degrees down).
      const Eigen::Vector3d d = p - q.position;
      below_level += expected && d.z() < -std::tan(M_PI / 6) * d.head<2>().norm() ? 1 : 0;
    }
    EXPECT_GT(inside, 500) << pitch_deg;
    // Only a camera pitched down sees below the level camera's FOV.
    if (pitch_deg > 0.0) {
      EXPECT_GT(below_level, 0);
    } else {
      EXPECT_EQ(below_level, 0) << pitch_deg;
    }
  }
}

TEST(VisibilityEvaluator, SameSetsForAnyThreadCount) {
  TsdfMap map(gridConfig(Eigen::Vector3i(48, 48, 24)));
  std::mt19937 rng(29);
  std::uniform_int_distribution<int> pick(0, 19);
  std::vector<Ise> ises;
  const Eigen::Vector3i& g = map.gridVoxels();
  for (int z = 0; z < g.z(); ++z)
    for (int y = 0; y < g.y(); ++y)
      for (int x = 0; x < g.x(); ++x) {
        const int p = pick(rng);
        setState(&map, Eigen::Vector3i(x, y, z), p == 0 ? VoxelState::kOccupied : VoxelState::kFree);
        if (p == 1) ises.push_back(iseAt(map, Eigen::Vector3i(x, y, z)));
      }
  std::vector<Viewpoint> viewpoints(40);
  std::uniform_real_distribution<double> u(1.0, 11.0), yaw(-M_PI, M_PI);
  for (Viewpoint& q : viewpoints) {
    q.position = Eigen::Vector3d(u(rng), u(rng), 0.5 * u(rng));
    q.yaw = yaw(rng);
  }
  const VoxelStateGrid grid = gridOf(map);
  const VoxelRayCaster rays(grid, true);
  SurfaceConfig one = testSurfaceConfig(), two = testSurfaceConfig();
  two.threads = 2;
  std::vector<Viewpoint> a = viewpoints, b = viewpoints;
  const uint64_t steps_a = VisibilityEvaluator(one).evaluate(rays, ises, &a);
  const uint64_t steps_b = VisibilityEvaluator(two).evaluate(rays, ises, &b);
  EXPECT_EQ(steps_a, steps_b);
  size_t total = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].visible, b[i].visible);
    total += a[i].visible.size();
    // Brute force: every ISE in the frustum with a clear ray.
    std::vector<uint32_t> expected;
    for (size_t k = 0; k < ises.size(); ++k) {
      uint64_t steps = 0;
      if (VisibilityEvaluator(one).inFrustum(viewpoints[i], ises[k].position) &&
          rays.clear(viewpoints[i].position, ises[k].voxel, &steps)) {
        expected.push_back(static_cast<uint32_t>(k));
      }
    }
    EXPECT_EQ(a[i].visible, expected);
  }
  EXPECT_GT(total, 50u);
}
