#include "surface_nbv/surface/frontier_builder.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "surface_test_maps.h"

using namespace surface_nbv;
using namespace surface_nbv::test;

namespace {

// 16 x 16 x 8 m: ground, a 4 x 4 x 3.75 m building and a pillar; the half
// x < 8 m has been scanned (free or occupied), the rest is unknown.
TsdfMap halfScannedSite(int known_x = 32) {
  TsdfMap map(gridConfig(Eigen::Vector3i(64, 64, 32)));
  fillBox(&map, Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(known_x, 64, 32), VoxelState::kFree);
  auto solid = [&](const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
    fillBox(&map, lo, Eigen::Vector3i(std::min(hi.x(), known_x), hi.y(), hi.z()), VoxelState::kOccupied);
  };
  solid(Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(64, 64, 1));     // ground
  solid(Eigen::Vector3i(24, 24, 1), Eigen::Vector3i(40, 40, 16));  // building
  solid(Eigen::Vector3i(12, 44, 1), Eigen::Vector3i(14, 46, 24));  // pillar
  return map;
}

void expectSameFrontier(const Frontier& a, const Frontier& b) {
  ASSERT_EQ(a.ises.size(), b.ises.size());
  for (size_t i = 0; i < a.ises.size(); ++i) {
    ASSERT_EQ(a.ises[i].id, b.ises[i].id);
    ASSERT_EQ(a.ises[i].remaining, b.ises[i].remaining);
    ASSERT_EQ(a.ises[i].viewpoint, b.ises[i].viewpoint);
    ASSERT_EQ(a.ises[i].direction, b.ises[i].direction);
    ASSERT_EQ(a.ises[i].approach, b.ises[i].approach);
    ASSERT_EQ(a.ises[i].unknown_blocked, b.ises[i].unknown_blocked);
  }
  EXPECT_EQ(a.remaining, b.remaining);
  EXPECT_EQ(a.scanned, b.scanned);
  ASSERT_EQ(a.viewpoints.size(), b.viewpoints.size());
  for (size_t i = 0; i < a.viewpoints.size(); ++i) {
    ASSERT_EQ(a.viewpoints[i].position, b.viewpoints[i].position);
    ASSERT_EQ(a.viewpoints[i].yaw, b.viewpoints[i].yaw);
    ASSERT_EQ(a.viewpoints[i].view_direction, b.viewpoints[i].view_direction);
    ASSERT_EQ(a.viewpoints[i].unknown_fraction, b.viewpoints[i].unknown_fraction);
    ASSERT_EQ(a.viewpoints[i].sources, b.viewpoints[i].sources);
    ASSERT_EQ(a.viewpoints[i].visible, b.viewpoints[i].visible);
    ASSERT_EQ(a.viewpoints[i].cluster, b.viewpoints[i].cluster);
  }
  ASSERT_EQ(a.clusters.size(), b.clusters.size());
  for (size_t i = 0; i < a.clusters.size(); ++i) {
    ASSERT_EQ(a.clusters[i].viewpoints, b.clusters[i].viewpoints);
    ASSERT_EQ(a.clusters[i].gain, b.clusters[i].gain);
  }
  EXPECT_EQ(a.stats.voxel_steps, b.stats.voxel_steps);
  EXPECT_EQ(a.stats.poses_tested, b.stats.poses_tested);
}

// 60 x 12 x 6 m: ground and five 2 x 3 x 3 m buildings 12 m apart, scanned
// for x < known_x voxels; beside the first building an unknown pocket
// that is never scanned keeps ISEs far from where the scan goes on (and,
// once the scan is past it, one beside the last building).
TsdfMap rowOfBuildings(int known_x) {
  TsdfMap map(gridConfig(Eigen::Vector3i(240, 48, 24)));
  fillBox(&map, Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(known_x, 48, 24), VoxelState::kFree);
  auto solid = [&](const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
    if (lo.x() >= known_x) return;
    fillBox(&map, lo, Eigen::Vector3i(std::min(hi.x(), known_x), hi.y(), hi.z()), VoxelState::kOccupied);
  };
  solid(Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(240, 48, 1));
  for (int x = 16; x < 240; x += 48) solid(Eigen::Vector3i(x, 18, 1), Eigen::Vector3i(x + 8, 30, 13));
  fillBox(&map, Eigen::Vector3i(24, 20, 1), Eigen::Vector3i(28, 28, 6), VoxelState::kUnknown);  // the pocket
  if (known_x > 216) {  // and one beside the last building
    fillBox(&map, Eigen::Vector3i(216, 20, 1), Eigen::Vector3i(220, 28, 6), VoxelState::kUnknown);
  }
  return map;
}

// Copies the blocks of `from` that differ into `map`, stamped as changed.
void copyChangedBlocks(const TsdfMap& from, TsdfMap* map) {
  for (const auto& b : from.blocks()) {
    TsdfBlock* dst = map->allocateBlock(b->index);
    bool same = true;
    for (int i = 0; i < kBlockVoxels && same; ++i) {
      same = dst->voxels[i].w == b->voxels[i].w && dst->voxels[i].phi == b->voxels[i].phi;
    }
    if (same) continue;
    dst->voxels = b->voxels;
    dst->change_stamp = map->beginChange();
  }
}

}  // namespace

TEST(FrontierBuilder, AnIseInsideANarrowSlotIsInCrem) {
  // A solid block with a one-voxel slot entering its -y face and turning
  // towards +x; the end of the slot is unseen.
  TsdfMap map(gridConfig(Eigen::Vector3i(40, 40, 24)));
  fillAll(&map, VoxelState::kFree);
  fillBox(&map, Eigen::Vector3i(10, 10, 0), Eigen::Vector3i(30, 30, 20), VoxelState::kOccupied);
  fillBox(&map, Eigen::Vector3i(20, 10, 10), Eigen::Vector3i(21, 20, 11), VoxelState::kFree);
  fillBox(&map, Eigen::Vector3i(21, 19, 10), Eigen::Vector3i(26, 20, 11), VoxelState::kFree);
  fillBox(&map, Eigen::Vector3i(26, 18, 9), Eigen::Vector3i(27, 21, 12), VoxelState::kUnknown);
  const auto collision = collisionFor(map);
  FrontierBuilder builder(testSurfaceConfig());
  Frontier frontier;
  ASSERT_TRUE(builder.update(map, *collision, &frontier).ok());
  ASSERT_EQ(frontier.ises.size(), 1u);
  EXPECT_EQ(frontier.ises[0].voxel, Eigen::Vector3i(25, 19, 10));
  EXPECT_NEAR((frontier.ises[0].direction - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-12);  // a direction exists ...
  EXPECT_TRUE(frontier.ises[0].remaining);                          // ... but no pose sees it
  EXPECT_EQ(frontier.ises[0].viewpoint, -1);
  EXPECT_FALSE(frontier.ises[0].unknown_blocked);  // no candidate waits on unknown space
  EXPECT_EQ(frontier.remaining, 1u);
  EXPECT_EQ(frontier.remaining_unknown, 0u);
  EXPECT_TRUE(frontier.viewpoints.empty());
  EXPECT_TRUE(frontier.clusters.empty());
  EXPECT_TRUE(frontier.complete());  // C_rem does not keep the mission alive
  EXPECT_GT(frontier.stats.poses_tested, 20u);
}

TEST(FrontierBuilder, IsesWhosePosesLieInUnknownSpaceAreMarked) {
  // The half-scanned wall of the extractor test: a 6 x 6 x 4 m world where
  // the known free space is 2 m deep and every candidate pose is too close
  // to the wall, the bounds or unknown space, some of them inside the latter.
  TsdfMap map(gridConfig(Eigen::Vector3i(24, 24, 16)));
  fillBox(&map, Eigen::Vector3i(12, 0, 0), Eigen::Vector3i(13, 12, 16), VoxelState::kOccupied);
  fillBox(&map, Eigen::Vector3i(4, 0, 0), Eigen::Vector3i(12, 12, 16), VoxelState::kFree);
  const auto collision = collisionFor(map);
  FrontierBuilder builder(testSurfaceConfig());
  Frontier frontier;
  ASSERT_TRUE(builder.update(map, *collision, &frontier).ok());
  ASSERT_EQ(frontier.ises.size(), 16u);
  EXPECT_EQ(frontier.remaining, 16u);
  EXPECT_EQ(frontier.remaining_unknown, 16u);
  for (const Ise& ise : frontier.ises) EXPECT_TRUE(ise.unknown_blocked);
}

TEST(FrontierBuilder, FrontierIsConsistent) {
  const TsdfMap map = halfScannedSite();
  const auto collision = collisionFor(map);
  const SurfaceConfig config = testSurfaceConfig();
  FrontierBuilder builder(config);
  Frontier f;
  ASSERT_TRUE(builder.update(map, *collision, &f).ok());
  ASSERT_GT(f.ises.size(), 50u);
  EXPECT_FALSE(f.complete());
  EXPECT_GT(f.viewpoints.size(), 3u);
  EXPECT_LT(f.viewpoints.size(), f.stats.unmerged_viewpoints);
  EXPECT_EQ(f.stats.unmerged_viewpoints, f.insideCount());
  EXPECT_TRUE(f.stats.full_extraction);
  size_t remaining = 0, sources = 0;
  for (size_t i = 0; i < f.ises.size(); ++i) {
    const Ise& ise = f.ises[i];
    EXPECT_EQ(ise.id, static_cast<uint64_t>(ise.voxel.x() + 64 * (ise.voxel.y() + 64 * ise.voxel.z())));
    EXPECT_EQ(map.state(ise.voxel), VoxelState::kFree);
    EXPECT_NEAR(ise.direction.norm(), 1.0, 1e-12);
    if (ise.remaining) {
      ++remaining;
      EXPECT_EQ(ise.viewpoint, -1);
      continue;
    }
    ASSERT_GE(ise.viewpoint, 0);
    const auto& s = f.viewpoints[ise.viewpoint].sources;
    EXPECT_TRUE(std::binary_search(s.begin(), s.end(), static_cast<uint32_t>(i)));
  }
  EXPECT_EQ(remaining, f.remaining);
  size_t clustered = 0;
  for (const Viewpoint& q : f.viewpoints) {
    sources += q.sources.size();
    EXPECT_TRUE(map.config().bounds.contains(q.position));
    EXPECT_TRUE(collision->isFree(q.position, config.collision_radius));
    EXPECT_TRUE(std::is_sorted(q.visible.begin(), q.visible.end()));
    // A viewpoint made of one pose sees the ISE it was made for.
    if (q.sources.size() == 1) {
      EXPECT_TRUE(std::binary_search(q.visible.begin(), q.visible.end(), q.sources[0]));
    }
    ASSERT_GE(q.cluster, 0);
    ASSERT_LT(q.cluster, static_cast<int>(f.clusters.size()));
  }
  EXPECT_EQ(sources, f.insideCount());
  for (size_t c = 0; c < f.clusters.size(); ++c) {
    clustered += f.clusters[c].viewpoints.size();
    for (uint32_t i : f.clusters[c].viewpoints) EXPECT_EQ(f.viewpoints[i].cluster, static_cast<int>(c));
    EXPECT_DOUBLE_EQ(f.clusters[c].gain, static_cast<double>(f.clusters[c].visible_ises) / f.ises.size());
    EXPECT_GT(f.clusters[c].gain, 0.0);
  }
  EXPECT_EQ(clustered, f.viewpoints.size());
  EXPECT_GT(f.stats.voxel_steps, 0u);
  EXPECT_GE(f.stats.total_ms, f.stats.ise_ms + f.stats.viewpoints_ms + f.stats.visibility_ms - 1e-6);
}

TEST(FrontierBuilder, SameFrontierForAnyThreadCount) {
  const TsdfMap map = halfScannedSite();
  const auto collision = collisionFor(map);
  SurfaceConfig one = testSurfaceConfig(), two = testSurfaceConfig();
  two.threads = 2;
  Frontier a, b;
  ASSERT_TRUE(FrontierBuilder(one).update(map, *collision, &a).ok());
  ASSERT_TRUE(FrontierBuilder(two).update(map, *collision, &b).ok());
  expectSameFrontier(a, b);
}

TEST(FrontierBuilder, IncrementalUpdateEqualsAFreshBuild) {
  TsdfMap map = halfScannedSite(20);
  auto collision = collisionFor(map);
  SurfaceConfig config = testSurfaceConfig();
  config.threads = 2;
  FrontierBuilder builder(config);
  Frontier incremental;
  ASSERT_TRUE(builder.update(map, *collision, &incremental).ok());
  for (int known_x : {28, 36, 48}) {
    const TsdfMap more = halfScannedSite(known_x);
    copyChangedBlocks(more, &map);  // the newly scanned blocks, stamped
    collision->update(map);
    ASSERT_TRUE(builder.update(map, *collision, &incremental).ok());
    EXPECT_FALSE(incremental.stats.full_extraction);
    EXPECT_EQ(incremental.stats.blocks_changed, 64u);  // two block columns of 8 x 4 newly scanned
    EXPECT_LT(incremental.stats.blocks_examined, map.numBlocks());
    Frontier fresh;
    ASSERT_TRUE(FrontierBuilder(config).update(map, *collision, &fresh).ok());
    expectSameFrontier(incremental, fresh);
  }
}

// An ISE far from every changed voxel keeps its n_v and pose search, and a
// viewpoint far from them its C_q: the same frontier as a builder that
// searches every pose and evaluates every viewpoint, through a scan that
// moves along the row, an update with nothing changed and a rebuilt
// collision map; stamped blocks whose states did not change are not changes.
TEST(FrontierBuilder, KeptPoseSearchesGiveTheFrontierOfSearchingAgain) {
  TsdfMap map = rowOfBuildings(64);
  auto collision = collisionFor(map);
  SurfaceConfig config = testSurfaceConfig();
  config.threads = 2;
  FrontierBuilder kept(config), searched(config);
  searched.setReusePoses(false);
  Frontier a, b;
  ASSERT_TRUE(kept.update(map, *collision, &a).ok());
  ASSERT_TRUE(searched.update(map, *collision, &b).ok());
  expectSameFrontier(a, b);
  EXPECT_EQ(a.stats.poses_reused, 0u) << "nothing to keep on the first update";
  size_t reused = 0, searched_again = 0, views_kept = 0;
  for (int known_x : {112, 160, 208, 240}) {
    copyChangedBlocks(rowOfBuildings(known_x), &map);
    collision->update(map);
    ASSERT_TRUE(kept.update(map, *collision, &a).ok());
    ASSERT_TRUE(searched.update(map, *collision, &b).ok());
    expectSameFrontier(a, b);
    EXPECT_EQ(b.stats.poses_reused, 0u);
    reused += a.stats.poses_reused;
    views_kept += a.stats.views_reused;
    EXPECT_EQ(b.stats.views_reused, 0u);
    searched_again += a.ises.size() - a.stats.poses_reused;
  }
  EXPECT_GT(reused, 0u) << "the pocket's ISEs are far from the scan";
  EXPECT_GT(searched_again, 0u) << "those near it are searched again";
  EXPECT_GT(views_kept, 0u);

  // Blocks stamped with the same states: every pose is kept.
  for (const auto& block : map.blocks()) map.mutableBlock(block->index)->change_stamp = map.beginChange();
  collision->update(map);
  ASSERT_TRUE(kept.update(map, *collision, &a).ok());
  ASSERT_TRUE(searched.update(map, *collision, &b).ok());
  expectSameFrontier(a, b);
  EXPECT_GT(a.stats.blocks_changed, 0u);
  EXPECT_EQ(a.stats.poses_reused, a.ises.size());
  EXPECT_EQ(a.stats.views_reused, a.viewpoints.size());

  // One voxel of the last pocket scanned: its ISEs are searched again, the first pocket's kept.
  setState(&map, Eigen::Vector3i(219, 20, 3), VoxelState::kFree);
  collision->update(map);
  ASSERT_TRUE(kept.update(map, *collision, &a).ok());
  ASSERT_TRUE(searched.update(map, *collision, &b).ok());
  expectSameFrontier(a, b);
  EXPECT_GT(a.stats.poses_reused, 0u);
  EXPECT_LT(a.stats.poses_reused, a.ises.size());
  EXPECT_GT(a.stats.views_reused, 0u);
  EXPECT_LT(a.stats.views_reused, a.viewpoints.size());

  // An obstacle where the first pocket's first viewpoint stands, blocks away
  // from its ISEs: they search again and find other poses.
  const auto pocket = std::find_if(a.viewpoints.begin(), a.viewpoints.end(),
                                   [](const Viewpoint& q) { return q.position.x() < 15.0; });
  ASSERT_NE(pocket, a.viewpoints.end());
  const Eigen::Vector3d stood = pocket->position;
  const Eigen::Vector3i at = (stood / kVoxel).array().floor().cast<int>();
  fillBox(&map, at - Eigen::Vector3i::Ones(), at + Eigen::Vector3i::Constant(2), VoxelState::kOccupied);
  collision->update(map);
  ASSERT_TRUE(kept.update(map, *collision, &a).ok());
  ASSERT_TRUE(searched.update(map, *collision, &b).ok());
  expectSameFrontier(a, b);
  for (const Viewpoint& q : a.viewpoints) EXPECT_GT((q.position - stood).norm(), 0.5);

  // A rebuilt collision map: nothing is kept.
  collision->rebuild(map);
  ASSERT_TRUE(kept.update(map, *collision, &a).ok());
  ASSERT_TRUE(searched.update(map, *collision, &b).ok());
  expectSameFrontier(a, b);
  EXPECT_EQ(a.stats.poses_reused, 0u);
  EXPECT_EQ(a.stats.views_reused, 0u);
}

TEST(FrontierBuilder, RefusesACollisionMapOfAnotherGrid) {
  const TsdfMap map = halfScannedSite();
  const TsdfMap other(gridConfig(Eigen::Vector3i(32, 32, 32)));
  const auto collision = collisionFor(other);
  FrontierBuilder builder(testSurfaceConfig());
  Frontier f;
  f.remaining = 7;
  const Status s = builder.update(map, *collision, &f);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("collision map"), std::string::npos);
  EXPECT_EQ(f.remaining, 7u);
}

TEST(FrontierBuilder, UnknownFractionIsTheUnseenShareOfWhatAViewpointFaces) {
  const TsdfMap map = halfScannedSite();  // scanned for x < 8 m, unknown beyond
  const VoxelStateGrid grid = gridOf(map);
  const VoxelRayCaster rays(grid, false);
  const CameraConfig camera;  // 90 x 60 deg, 8 m
  Viewpoint v;
  v.position = Eigen::Vector3d(5.0, 4.0, 2.0);
  v.yaw = 0.0;  // towards +x: 3 m of scanned space, then the unknown half
  const double forward = unknownFraction(rays, v, camera);
  v.yaw = M_PI;  // towards -x: scanned space up to the grid's face
  const double backward = unknownFraction(rays, v, camera);
  EXPECT_GT(forward, 0.3);
  EXPECT_LT(forward, 1.0);
  EXPECT_EQ(backward, 0.0);
  v.position = Eigen::Vector3d(-5.0, -5.0, 2.0);
  EXPECT_EQ(unknownFraction(rays, v, camera), 1.0) << "outside the grid: not evaluated";

  // The builder fills it in for every viewpoint, or leaves 1 when told not to.
  const auto collision = collisionFor(map);
  for (bool evaluate : {true, false}) {
    SurfaceConfig config = testSurfaceConfig();
    config.unknown_fraction = evaluate;
    FrontierBuilder builder(config);
    Frontier frontier;
    ASSERT_TRUE(builder.update(map, *collision, &frontier).ok());
    ASSERT_FALSE(frontier.viewpoints.empty());
    double lowest = 1.0;
    for (const Viewpoint& w : frontier.viewpoints) {
      EXPECT_GE(w.unknown_fraction, 0.0);
      EXPECT_LE(w.unknown_fraction, 1.0);
      lowest = std::min(lowest, w.unknown_fraction);
    }
    if (evaluate) {
      EXPECT_LT(lowest, 1.0);
    } else {
      EXPECT_EQ(lowest, 1.0);
    }
  }
}
