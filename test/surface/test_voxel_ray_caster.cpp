#include "surface_nbv/surface/voxel_ray_caster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "surface_test_maps.h"

using namespace surface_nbv;
using namespace surface_nbv::test;

namespace {

Eigen::Vector3i voxelOfIndex(const VoxelStateGrid& grid, size_t index) {
  const int64_t i = static_cast<int64_t>(index);
  const int64_t z = i / grid.strideZ(), rest = i % grid.strideZ();
  return Eigen::Vector3i(static_cast<int>(rest % grid.strideY()) - 1, static_cast<int>(rest / grid.strideY()) - 1,
                         static_cast<int>(z) - 1);
}

// Does the segment a -> b (voxel units) meet the unit cube at v (with a tolerance)?
bool segmentMeetsVoxel(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3i& v) {
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k], lo = v[k] - 1e-9, hi = v[k] + 1 + 1e-9;
    if (std::abs(d) < 1e-15) {
      if (a[k] < lo || a[k] > hi) return false;
      continue;
    }
    double ta = (lo - a[k]) / d, tb = (hi - a[k]) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

}  // namespace

TEST(VoxelRayCaster, WalksExactlyTheVoxelsTheSegmentCrosses) {
  TsdfMap map(gridConfig(Eigen::Vector3i(30, 20, 25)));
  const VoxelStateGrid grid = gridOf(map);
  const VoxelRayCaster rays(grid, false);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> ux(0.0, 30.0), uy(0.0, 20.0), uz(0.0, 25.0);
  std::uniform_int_distribution<int> ix(0, 29), iy(0, 19), iz(0, 24);
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Vector3d from(ux(rng), uy(rng), uz(rng));  // voxel units
    const Eigen::Vector3i target(ix(rng), iy(rng), iz(rng));
    const Eigen::Vector3d to = target.cast<double>().array() + 0.5;
    std::vector<Eigen::Vector3i> walked;
    uint64_t steps = 0;
    ASSERT_TRUE(rays.walk(grid.origin() + from * kVoxel, target, &steps, [&](size_t i) {
      walked.push_back(voxelOfIndex(grid, i));
      return true;
    }));
    const Eigen::Vector3i start = from.array().floor().cast<int>();
    const int manhattan = (target - start).cwiseAbs().sum();
    ASSERT_EQ(static_cast<int>(walked.size()), std::max(0, manhattan - 1));
    EXPECT_EQ(steps, walked.size());
    Eigen::Vector3i previous = start;
    for (const Eigen::Vector3i& v : walked) {
      ASSERT_EQ((v - previous).cwiseAbs().sum(), 1) << "not 6-connected";
      ASSERT_TRUE(segmentMeetsVoxel(from, to, v)) << v.transpose();
      previous = v;
    }
    if (manhattan > 0) {
      EXPECT_EQ((target - previous).cwiseAbs().sum(), 1);
    }
    // Walking back from the target visits the same voxels in reverse.
    std::vector<Eigen::Vector3i> back;
    uint64_t back_steps = 0;
    ASSERT_TRUE(rays.walkBack(rays.origin(grid.origin() + from * kVoxel), target, &back_steps, [&](size_t i) {
      back.push_back(voxelOfIndex(grid, i));
      return true;
    }));
    std::reverse(back.begin(), back.end());
    ASSERT_EQ(back, walked);
    EXPECT_EQ(back_steps, steps);
  }
}

TEST(VoxelRayCaster, OccupiedBlocksAndUnknownBlocksOnlyWhenAsked) {
  TsdfMap map(gridConfig(Eigen::Vector3i(32, 8, 8)));
  fillAll(&map, VoxelState::kFree);
  const Eigen::Vector3d from = map.voxelCenter(Eigen::Vector3i(1, 4, 4));
  const Eigen::Vector3i target(30, 4, 4);
  uint64_t steps = 0;
  EXPECT_TRUE(VoxelRayCaster(gridOf(map), true).clear(from, target, &steps));
  EXPECT_EQ(steps, 28u);
  setState(&map, Eigen::Vector3i(10, 4, 4), VoxelState::kUnknown);
  {
    const VoxelStateGrid grid = gridOf(map);
    steps = 0;
    EXPECT_FALSE(VoxelRayCaster(grid, true).clear(from, target, &steps));
    EXPECT_EQ(steps, 20u);  // walked back from voxel 30, stopped on entering voxel 10
    EXPECT_TRUE(VoxelRayCaster(grid, false).clear(from, target, &steps));
  }
  setState(&map, Eigen::Vector3i(20, 4, 4), VoxelState::kOccupied);
  const VoxelStateGrid grid = gridOf(map);
  EXPECT_FALSE(VoxelRayCaster(grid, false).clear(from, target, &steps));
  // The target voxel itself and the start voxel never block.
  EXPECT_TRUE(VoxelRayCaster(grid, false).clear(from, Eigen::Vector3i(20, 4, 4), &steps));
  EXPECT_TRUE(VoxelRayCaster(grid, true).clear(map.voxelCenter(Eigen::Vector3i(10, 4, 4)), Eigen::Vector3i(12, 4, 4), &steps));
  // Outside the grid: no line of sight.
  EXPECT_FALSE(VoxelRayCaster(grid, false).clear(Eigen::Vector3d(-1, 1, 1), target, &steps));
  EXPECT_FALSE(VoxelRayCaster(grid, false).clear(from, Eigen::Vector3i(32, 4, 4), &steps));
}
