#include "surface_nbv/map/tsdf_integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>

#include "surface_nbv/sensor/depth_points.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/mesh_builder.h"

using namespace surface_nbv;

namespace {

// Optical frame looking along world +x (image x = -y, image y = -z).
Transform lookingAlongX(const Eigen::Vector3d& position) {
  Transform T = Transform::Identity();
  T.linear().col(0) = Eigen::Vector3d(0, -1, 0);
  T.linear().col(1) = Eigen::Vector3d(0, 0, -1);
  T.linear().col(2) = Eigen::Vector3d(1, 0, 0);
  T.translation() = position;
  return T;
}

// A world with a large wall at x = wall_x, rendered by the simulator.
struct WallWorld {
  double wall_x = 5.0;
  TriangleMesh mesh;
  std::unique_ptr<RaycastScene> scene;
  CameraConfig camera_config;

  WallWorld() {
    MeshBuilder b;
    b.addBox(Eigen::Vector3d(wall_x + 0.5, 0, 0), Eigen::Vector3d(1.0, 200.0, 200.0));
    mesh = b.take();
    EXPECT_TRUE(RaycastScene::create(mesh, &scene).ok());
    camera_config.width = 160;
    camera_config.height = 120;
  }
  DepthImage render(const Transform& T_W_C) const {
    DepthImage depth;
    DepthRenderer(*scene, DepthCamera(camera_config), 1).render(T_W_C, &depth);
    return depth;
  }
};

TsdfConfig wallConfig() {
  TsdfConfig c;
  c.voxel_size = 0.2;
  c.bounds = AlignedBox(Eigen::Vector3d(-1, -4, -3), Eigen::Vector3d(8, 4, 3));
  return c;
}

// One frame of the wall from (camera_x, 0, 0), for a map of wallConfig() and
// one of `variant`: the tests of an option against the plain map.
struct WallPair {
  WallPair(const TsdfConfig& variant, double camera_x)
      : plain_map(wallConfig()),
        variant_map(variant),
        plain(&plain_map),
        other(&variant_map),
        camera(world.camera_config),
        T(lookingAlongX(Eigen::Vector3d(camera_x, 0.0, 0.0))),
        depth(world.render(T)) {}

  WallWorld world;
  TsdfMap plain_map, variant_map;
  TsdfIntegrator plain, other;
  DepthCamera camera;
  Transform T;
  DepthImage depth;
};

}  // namespace

TEST(TsdfIntegrator, WallPhiIsExactAndWeightsSumInverseSquares) {
  WallWorld world;
  TsdfMap map(wallConfig());
  TsdfIntegrator integrator(&map);
  const DepthCamera camera(world.camera_config);
  const std::vector<double> cam_x = {0.0, 1.0, 1.5};
  for (double x : cam_x) {
    const Transform T = lookingAlongX(Eigen::Vector3d(x, 0.0, 0.0));
    ASSERT_TRUE(integrator.integrateDepth(camera, world.render(T), T).ok());
  }
  const double trunc = map.config().truncationDistance();
  int checked = 0;
  for (double y : {-0.5, 0.1, 0.7}) {
    for (double xc = 2.1; xc < 7.9; xc += 0.2) {
      Eigen::Vector3i v;
      ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(xc, y, 0.1), &v));
      const Eigen::Vector3d c = map.voxelCenter(v);
      const TsdfVoxel* vox = map.voxel(v);
      const double sdf = world.wall_x - c.x();
      if (sdf < -trunc) {
        EXPECT_TRUE(vox == nullptr || vox->w == 0.0f) << "updated behind the wall at x = " << c.x();
        continue;
      }
      ASSERT_NE(vox, nullptr) << c.transpose();
      double w = 0.0;
      for (double x : cam_x) {
        const double z = c.x() - x;  // depth of the voxel for this camera; inside the 90 x 60 FOV?
        if (std::abs(c.y()) <= z && std::abs(c.z()) <= z * std::tan(M_PI / 6)) w += 1.0 / (z * z);
      }
      EXPECT_NEAR(vox->w, w, 1e-5 * w) << c.transpose();
      EXPECT_NEAR(vox->phi, std::min(sdf, trunc), 1e-5) << c.transpose();
      ++checked;
    }
  }
  EXPECT_EQ(checked, 54);  // 3 rows x 18 voxels in front of or at the wall
}

// With weight_dropoff, an update behind the wall keeps its full weight down
// to one voxel behind, then the share (t + sdf) / (t - voxel) of it, and
// nothing at -t. The distances are the same as without, and so is
// everything in front.
TEST(TsdfIntegrator, WeightDropsOffBehindTheSurface) {
  TsdfConfig config = wallConfig();
  config.weight_dropoff = true;
  WallPair p(config, 1.0);
  const WallWorld& world = p.world;
  const TsdfMap &plain_map = p.plain_map, &dropped_map = p.variant_map;
  ASSERT_TRUE(p.plain.integrateDepth(p.camera, p.depth, p.T).ok());
  ASSERT_TRUE(p.other.integrateDepth(p.camera, p.depth, p.T).ok());
  const double trunc = config.truncationDistance(), voxel = config.voxel_size;
  int behind = 0, full = 0;
  for (double xc = 2.1; xc < 7.9; xc += 0.2) {
    Eigen::Vector3i v;
    ASSERT_TRUE(plain_map.voxelIndex(Eigen::Vector3d(xc, 0.1, 0.1), &v));
    const double sdf = world.wall_x - plain_map.voxelCenter(v).x();
    const TsdfVoxel* a = plain_map.voxel(v);
    const TsdfVoxel* b = dropped_map.voxel(v);
    if (sdf <= -trunc + 1e-6) {  // nothing left at -t, nothing at all beyond
      EXPECT_TRUE(b == nullptr || b->w == 0.0f) << xc;
      continue;
    }
    ASSERT_NE(a, nullptr) << xc;
    ASSERT_NE(b, nullptr) << xc;
    EXPECT_FLOAT_EQ(b->phi, a->phi) << xc;
    const double share = sdf < -voxel ? (trunc + sdf) / (trunc - voxel) : 1.0;
    EXPECT_NEAR(b->w, a->w * share, 1e-5 * a->w) << xc;
    (share < 1.0 ? behind : full) += 1;
  }
  EXPECT_EQ(behind, 2);  // 0.3 and 0.5 m behind the wall (t = 0.6 m)
  EXPECT_GE(full, 15);
  // Off by default: the same map as before.
  EXPECT_FALSE(TsdfConfig().weight_dropoff);
}

// band_allocation (the mesh layer's): no new block wholly in front of the
// wall by more than the truncation; blocks near the wall hold the same voxels
// as without; a block that exists is still updated however far in front.
TEST(TsdfIntegrator, BandAllocationKeepsBlocksNearSurfaces) {
  TsdfConfig config = wallConfig();
  config.band_allocation = true;
  WallPair p(config, 0.0);
  const WallWorld& world = p.world;
  const TsdfMap& full_map = p.plain_map;
  TsdfMap& band_map = p.variant_map;
  ASSERT_TRUE(p.plain.integrateDepth(p.camera, p.depth, p.T).ok());
  // A block 4 m in front of the wall, allocated before the frame.
  Eigen::Vector3i near_camera;
  ASSERT_TRUE(band_map.voxelIndex(Eigen::Vector3d(1.0, 0.0, 0.0), &near_camera));
  ASSERT_NE(band_map.allocateVoxel(near_camera), nullptr);
  ASSERT_TRUE(p.other.integrateDepth(p.camera, p.depth, p.T).ok());
  const double trunc = config.truncationDistance(), block_len = config.voxel_size * kBlockSize;
  size_t far_blocks = 0;
  for (const auto& b : full_map.blocks()) {
    const double x0 = config.bounds.min.x() + b->index.x() * block_len;
    if (x0 + block_len < world.wall_x - trunc) {
      far_blocks += 1;
      const bool kept = band_map.block(b->index) != nullptr;
      EXPECT_EQ(kept, b->index == TsdfMap::blockOfVoxel(near_camera)) << b->index.transpose();
      continue;
    }
    const TsdfBlock* kept = band_map.block(b->index);
    ASSERT_NE(kept, nullptr) << "a block within the truncation of the wall is missing: " << b->index.transpose();
    EXPECT_EQ(std::memcmp(kept->voxels.data(), b->voxels.data(), sizeof(b->voxels)), 0) << b->index.transpose();
  }
  EXPECT_GT(far_blocks, 10u);
  EXPECT_LT(band_map.numBlocks(), full_map.numBlocks());
  const TsdfVoxel* carved = band_map.voxel(near_camera);
  ASSERT_NE(carved, nullptr);
  EXPECT_GT(carved->w, 0.0f);  // updated: free space seen 4 m in front of the wall
  EXPECT_FLOAT_EQ(carved->phi, static_cast<float>(trunc));
}

TEST(TsdfIntegrator, StatesAfterRepeatedViews) {
  WallWorld world;
  TsdfMap map(wallConfig());
  TsdfIntegrator integrator(&map);
  const DepthCamera camera(world.camera_config);
  const Transform T = lookingAlongX(Eigen::Vector3d(0.0, 0.0, 0.0));
  const DepthImage depth = world.render(T);
  for (int i = 0; i < 12; ++i) ASSERT_TRUE(integrator.integrateDepth(camera, depth, T).ok());
  // 12 / z^2 >= 0.3 up to z = 6.3 m: free in front, occupied just behind the face.
  Eigen::Vector3i v;
  ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(3.0, 0.1, 0.1), &v));
  EXPECT_EQ(map.state(v), VoxelState::kFree);
  ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(5.1, 0.1, 0.1), &v));
  EXPECT_EQ(map.state(v), VoxelState::kOccupied);
  ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(4.9, 0.1, 0.1), &v));
  EXPECT_EQ(map.state(v), VoxelState::kFree);
  ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(6.0, 0.1, 0.1), &v));
  EXPECT_EQ(map.state(v), VoxelState::kUnknown);  // beyond the truncation band
  ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(3.0, 0.1, 2.9), &v));
  EXPECT_EQ(map.state(v), VoxelState::kUnknown);  // outside the vertical FOV at x = 3
}

// Zero crossing of phi within a quarter voxel of a sphere seen from a ring
// of poses; with clear_inf (the default) the sky beside the silhouette is
// carved too, which may move the crossing by a few millimetres more.
class SpherePhi : public ::testing::TestWithParam<InvalidPixelPolicy> {};

TEST_P(SpherePhi, NearSurfaceWithinAQuarterVoxel) {
  MeshBuilder b;
  const Eigen::Vector3d centre(0, 0, 0);
  const double r = 1.5;
  b.addSphere(centre, r, 96, 192);
  std::unique_ptr<RaycastScene> scene;
  ASSERT_TRUE(RaycastScene::create(b.mesh(), &scene).ok());
  CameraConfig cc;
  cc.width = 320;
  cc.height = 240;
  cc.min_range = 0.5;
  const DepthCamera camera(cc);
  TsdfConfig c;
  c.voxel_size = 0.1;
  c.bounds = AlignedBox(Eigen::Vector3d(-6, -6, -3), Eigen::Vector3d(6, 6, 3));
  c.invalid_pixels = GetParam();
  TsdfMap map(c);
  TsdfIntegrator integrator(&map);
  for (int k = 0; k < 24; ++k) {
    const double a = 2 * M_PI * k / 24;
    const Eigen::Vector3d pos(4.5 * std::cos(a), 4.5 * std::sin(a), 0.3);
    Transform T = Transform::Identity();
    const Eigen::Vector3d z = (centre - pos).normalized(), x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
    T.linear().col(0) = x;
    T.linear().col(1) = z.cross(x);
    T.linear().col(2) = z;
    T.translation() = pos;
    DepthImage depth;
    DepthRenderer(*scene, camera, 2).render(T, &depth);
    ASSERT_TRUE(integrator.integrateDepth(camera, depth, T).ok());
  }
  // Projective distances are inflated by 1 / cos(view angle) on both sides of
  // the surface, so the sign and the zero crossing are what must be right.
  int signs = 0, signs_right = 0;
  for (const auto& blk : map.blocks()) {
    for (int i = 0; i < kBlockVoxels; ++i) {
      const TsdfVoxel& v = blk->voxels[i];
      const Eigen::Vector3i idx = blk->index * kBlockSize + Eigen::Vector3i(i % 8, (i / 8) % 8, i / 64);
      const double truth = (map.voxelCenter(idx) - centre).norm() - r;
      if (v.w < c.w_th || std::abs(truth) < 0.5 * c.voxel_size || std::abs(truth) > 2 * c.voxel_size) continue;
      ++signs;
      signs_right += (v.phi > 0) == (truth > 0) ? 1 : 0;
    }
  }
  EXPECT_GT(signs, 2000);
  EXPECT_GT(static_cast<double>(signs_right) / signs, 0.995) << signs_right << " of " << signs;
  // Zero crossing of trilinearly interpolated phi along normals in the band
  // the cameras face (|elevation| < 30 deg).
  auto phiAt = [&](const Eigen::Vector3d& p, double* phi) {
    const Eigen::Vector3d f = (p - c.bounds.min) / c.voxel_size - Eigen::Vector3d::Constant(0.5);
    const Eigen::Vector3i i0 = f.array().floor().cast<int>();
    const Eigen::Vector3d t = f - i0.cast<double>();
    double sum = 0.0;
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3i d(k & 1, (k >> 1) & 1, (k >> 2) & 1);
      const TsdfVoxel* v = map.voxel(i0 + d);
      if (v == nullptr || v->w < c.w_th) return false;
      const double wt = (d.x() ? t.x() : 1 - t.x()) * (d.y() ? t.y() : 1 - t.y()) * (d.z() ? t.z() : 1 - t.z());
      sum += wt * v->phi;
    }
    *phi = sum;
    return true;
  };
  int crossings = 0;
  double worst = 0.0;
  for (int k = 0; k < 360; ++k) {
    const double az = 2 * M_PI * k / 360, el = (k % 7 - 3) * 0.15;
    const Eigen::Vector3d n(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    double lo = r - 1.5 * c.voxel_size, hi = r + 1.5 * c.voxel_size, phi_lo, phi_hi;
    if (!phiAt(centre + lo * n, &phi_lo) || !phiAt(centre + hi * n, &phi_hi) || phi_lo > 0 || phi_hi < 0) continue;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      double phi_mid;
      ASSERT_TRUE(phiAt(centre + mid * n, &phi_mid));
      (phi_mid > 0 ? hi : lo) = mid;
    }
    ++crossings;
    worst = std::max(worst, std::abs(0.5 * (lo + hi) - r));
  }
  EXPECT_GT(crossings, 240);
  EXPECT_LT(worst, (GetParam() == InvalidPixelPolicy::kIgnore ? 0.25 : 0.3) * c.voxel_size);
}

INSTANTIATE_TEST_SUITE_P(Policies, SpherePhi,
                         ::testing::Values(InvalidPixelPolicy::kIgnore, InvalidPixelPolicy::kClearInfinite));

TEST(TsdfIntegrator, InvalidPixelsIgnoredOrCleared) {
  WallWorld world;
  const DepthCamera camera(world.camera_config);
  const Transform T = lookingAlongX(Eigen::Vector3d(0.0, 0.0, 0.0));
  DepthImage depth = world.render(T);
  for (float& z : depth.data) z = NAN;  // the sensor saw nothing at all
  for (const bool clear : {false, true}) {
    TsdfConfig c = wallConfig();
    c.invalid_pixels = clear ? InvalidPixelPolicy::kClearToMaxRange : InvalidPixelPolicy::kIgnore;
    TsdfMap map(c);
    TsdfIntegrator integrator(&map);
    IntegrationStats stats;
    ASSERT_TRUE(integrator.integrateDepth(camera, depth, T, &stats).ok());
    EXPECT_EQ(stats.invalid_pixels, depth.data.size());
    Eigen::Vector3i near_v, far_v;
    ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(3.0, 0.1, 0.1), &near_v));
    ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(7.9, 0.1, 0.1), &far_v));
    if (!clear) {
      EXPECT_EQ(stats.voxels_updated, 0u);
      EXPECT_EQ(map.voxel(near_v) == nullptr ? 0.0f : map.voxel(near_v)->w, 0.0f);
    } else {
      ASSERT_NE(map.voxel(near_v), nullptr);
      EXPECT_NEAR(map.voxel(near_v)->w, 1.0 / (3.1 * 3.1), 1e-3);
      EXPECT_FLOAT_EQ(map.voxel(near_v)->phi, static_cast<float>(c.truncationDistance()));
      // Max range is 8 m: the voxel centred at 7.9 is cleared, none beyond the range.
      ASSERT_NE(map.voxel(far_v), nullptr);
      EXPECT_GT(map.voxel(far_v)->w, 0.0f);
    }
  }
}

TEST(TsdfIntegrator, TwoThreadsGiveTheSameMap) {
  WallWorld world;
  const DepthCamera camera(world.camera_config);
  std::vector<std::unique_ptr<TsdfMap>> maps;
  for (int threads : {1, 2}) {
    TsdfConfig c = wallConfig();
    c.threads = threads;
    maps.push_back(std::make_unique<TsdfMap>(c));
    TsdfIntegrator integrator(maps.back().get());
    for (double y : {-1.0, 0.0, 0.5}) {
      const Transform T = lookingAlongX(Eigen::Vector3d(0.5, y, 0.2));
      ASSERT_TRUE(integrator.integrateDepth(camera, world.render(T), T).ok());
    }
  }
  ASSERT_EQ(maps[0]->numBlocks(), maps[1]->numBlocks());
  for (const auto& b : maps[0]->blocks()) {
    const TsdfBlock* other = maps[1]->block(b->index);
    ASSERT_NE(other, nullptr);
    EXPECT_EQ(std::memcmp(b->voxels.data(), other->voxels.data(), sizeof(b->voxels)), 0);
  }
}

// A frame of weight scale 3 equals the same frame integrated three times.
TEST(TsdfIntegrator, WeightScaleCountsAFrameAsSeveral) {
  WallWorld world;
  const DepthCamera camera(world.camera_config);
  const Transform T = lookingAlongX(Eigen::Vector3d(0.5, 0.0, 0.2));
  const DepthImage depth = world.render(T);
  TsdfMap once(wallConfig()), thrice(wallConfig());
  TsdfIntegrator scaled(&once), plain(&thrice);
  scaled.setWeightScale(3.0);
  scaled.setWeightScale(-1.0);  // ignored
  EXPECT_FLOAT_EQ(scaled.weightScale(), 3.0f);
  ASSERT_TRUE(scaled.integrateDepth(camera, depth, T).ok());
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(plain.integrateDepth(camera, depth, T).ok());
  ASSERT_EQ(once.numBlocks(), thrice.numBlocks());
  size_t compared = 0;
  for (const auto& b : once.blocks()) {
    const TsdfBlock* other = thrice.block(b->index);
    ASSERT_NE(other, nullptr);
    for (int i = 0; i < kBlockVoxels; ++i) {
      ASSERT_NEAR(b->voxels[i].w, other->voxels[i].w, 1e-5f * std::max(1.0f, other->voxels[i].w));
      ASSERT_NEAR(b->voxels[i].phi, other->voxels[i].phi, 1e-5f);
      compared += other->voxels[i].w > 0.0f;
    }
  }
  EXPECT_GT(compared, 1000u);
}

TEST(TsdfIntegrator, RefusesBadInputAndLeavesMapUnchanged) {
  WallWorld world;
  const DepthCamera camera(world.camera_config);
  TsdfMap map(wallConfig());
  TsdfIntegrator integrator(&map);
  const Transform T = lookingAlongX(Eigen::Vector3d(0.0, 0.0, 0.0));
  DepthImage depth = world.render(T);
  Transform outside = T;
  outside.translation().x() = 50.0;
  Status s = integrator.integrateDepth(camera, depth, outside);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("outside"), std::string::npos);
  Transform nan_pose = T;
  nan_pose.translation().y() = NAN;
  EXPECT_FALSE(integrator.integrateDepth(camera, depth, nan_pose).ok());
  DepthImage small;
  small.resize(10, 10);
  EXPECT_FALSE(integrator.integrateDepth(camera, small, T).ok());
  EXPECT_FALSE(integrator.integratePoints({Eigen::Vector3f(1, 0, 0)}, nan_pose, 8.0).ok());
  EXPECT_EQ(map.numBlocks(), 0u);
  EXPECT_EQ(map.changeCounter(), 0u);
}

TEST(TsdfIntegrator, WeightCapHolds) {
  WallWorld world;
  const DepthCamera camera(world.camera_config);
  TsdfConfig c = wallConfig();
  c.max_weight = 0.5f;
  TsdfMap map(c);
  TsdfIntegrator integrator(&map);
  const Transform T = lookingAlongX(Eigen::Vector3d(0.0, 0.0, 0.0));
  const DepthImage depth = world.render(T);
  for (int i = 0; i < 20; ++i) ASSERT_TRUE(integrator.integrateDepth(camera, depth, T).ok());
  Eigen::Vector3i v;
  ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(1.0, 0.0, 0.0), &v));
  EXPECT_FLOAT_EQ(map.voxel(v)->w, 0.5f);
}

TEST(TsdfIntegrator, PointCloudMakesTheSameKindOfMap) {
  WallWorld world;
  const DepthCamera camera(world.camera_config);
  TsdfMap from_depth(wallConfig()), from_points(wallConfig());
  TsdfIntegrator a(&from_depth), b(&from_points);
  const Transform T = lookingAlongX(Eigen::Vector3d(0.0, 0.0, 0.0));
  const DepthImage depth = world.render(T);
  std::vector<Eigen::Vector3f> points_C;
  ASSERT_TRUE(depthToPoints(camera, depth, &points_C));
  for (int i = 0; i < 12; ++i) {
    ASSERT_TRUE(a.integrateDepth(camera, depth, T).ok());
    ASSERT_TRUE(b.integratePoints(points_C, T, 8.0).ok());
  }
  // Along the optical axis the two agree exactly (the ray is the z axis).
  Eigen::Vector3i v;
  ASSERT_TRUE(from_points.voxelIndex(Eigen::Vector3d(4.7, 0.1, 0.1), &v));
  ASSERT_NE(from_points.voxel(v), nullptr);
  EXPECT_NEAR(from_points.voxel(v)->phi, from_depth.voxel(v)->phi, 0.05);
  size_t both = 0, agree = 0;
  for (const auto& blk : from_depth.blocks()) {
    for (int i = 0; i < kBlockVoxels; ++i) {
      const Eigen::Vector3i idx = blk->index * kBlockSize + Eigen::Vector3i(i % 8, (i / 8) % 8, i / 64);
      const VoxelState s1 = from_depth.state(idx), s2 = from_points.state(idx);
      if (s1 == VoxelState::kUnknown || s2 == VoxelState::kUnknown) continue;
      ++both;
      agree += s1 == s2 ? 1 : 0;
    }
  }
  EXPECT_GT(both, 1000u);
  EXPECT_GT(static_cast<double>(agree) / both, 0.97);
}
