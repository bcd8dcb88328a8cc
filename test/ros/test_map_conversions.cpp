#include "surface_nbv/ros/map_conversions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace surface_nbv;

namespace {

TsdfConfig smallConfig() {
  TsdfConfig config;
  config.voxel_size = 0.2;
  config.w_th = 0.25f;
  config.bounds = AlignedBox(Eigen::Vector3d(-3.2, -1.6, 0.0), Eigen::Vector3d(3.2, 1.6, 3.2));
  return config;
}

// A map of a few blocks with distinct, reproducible values.
void fill(TsdfMap* map) {
  const Eigen::Vector3i indices[] = {{0, 0, 0}, {3, 1, 1}, {2, 0, 1}};
  for (int b = 0; b < 3; ++b) {
    TsdfBlock* block = map->allocateBlock(indices[b]);
    ASSERT_NE(block, nullptr);
    for (int i = 0; i < kBlockVoxels; ++i) {
      block->voxels[i].phi = std::sin(0.37f * i + b) * 0.6f;
      block->voxels[i].w = 0.01f * ((i * 7 + b) % 300);
    }
    block->voxels[5].phi = -0.0f;
    block->change_stamp = map->beginChange();
  }
}

TsdfUpdate snapshotMsg(const TsdfMap& map, uint64_t sequence) {
  MapUpdate update;
  EXPECT_TRUE(makeUpdate(map, 0, sequence, true, &update).ok());
  std_msgs::Header header;
  header.frame_id = "world";
  header.stamp = ros::Time(12, 500);
  TsdfUpdate msg;
  toUpdateMsg(update, header, &msg);
  return msg;
}

MapUpdate fromMsg(const TsdfUpdate& msg) {
  MapUpdate update;
  fromUpdateMsg(msg, &update);
  return update;
}

}  // namespace

TEST(MapConversions, MessageRoundTripIsBitIdentical) {
  TsdfMap map(smallConfig());
  fill(&map);
  const TsdfUpdate msg = snapshotMsg(map, 41);
  EXPECT_EQ(msg.header.frame_id, "world");
  EXPECT_EQ(msg.header.stamp, ros::Time(12, 500));
  EXPECT_EQ(msg.sequence, 41u);
  EXPECT_TRUE(msg.snapshot);
  EXPECT_EQ(msg.voxel_size, 0.2);
  EXPECT_EQ(msg.w_th, 0.25f);
  EXPECT_EQ(msg.bounds_min.x, -3.2);
  EXPECT_EQ(msg.bounds_max.z, 3.2);
  ASSERT_EQ(msg.blocks.size(), 3u);
  EXPECT_EQ(msg.blocks[1].x, 3);
  EXPECT_EQ(msg.blocks[1].z, 1);
  EXPECT_EQ(msg.blocks[1].phi.size(), static_cast<size_t>(kBlockVoxels));

  const MapUpdate back = fromMsg(msg);
  EXPECT_EQ(back.sequence, 41u);
  EXPECT_TRUE(back.snapshot);
  EXPECT_EQ(back.bounds.min, smallConfig().bounds.min);
  EXPECT_EQ(back.bounds.max, smallConfig().bounds.max);

  MapMirror mirror(smallConfig());
  ASSERT_EQ(mirror.apply(back), ApplyResult::kApplied) << mirror.lastError();
  ASSERT_EQ(mirror.map().numBlocks(), 3u);
  for (const auto& b : map.blocks()) {
    const TsdfBlock* copy = mirror.map().block(b->index);
    ASSERT_NE(copy, nullptr);
    EXPECT_EQ(std::memcmp(copy->voxels.data(), b->voxels.data(), sizeof(b->voxels)), 0);
  }

  // An incremental message follows on.
  TsdfUpdate next = snapshotMsg(map, 42);
  next.snapshot = false;
  next.blocks.resize(1);
  next.blocks[0].w[100] = 9.5f;
  ASSERT_EQ(mirror.apply(fromMsg(next)), ApplyResult::kApplied) << mirror.lastError();
  EXPECT_EQ(mirror.map().block({0, 0, 0})->voxels[100].w, 9.5f);
}

TEST(MapConversions, MalformedMessagesAreRefusedByTheMirror) {
  TsdfMap map(smallConfig());
  fill(&map);
  const TsdfUpdate good = snapshotMsg(map, 1);
  MapMirror mirror(smallConfig());

  std::vector<std::pair<std::string, TsdfUpdate>> bad;
  auto variant = [&](const std::string& name, auto&& edit) {
    TsdfUpdate m = good;
    edit(m);
    bad.emplace_back(name, m);
  };
  variant("phi short", [](TsdfUpdate& m) { m.blocks[2].phi.resize(511); });
  variant("w long", [](TsdfUpdate& m) { m.blocks[2].w.resize(513, 1.0f); });
  variant("arrays missing", [](TsdfUpdate& m) { m.blocks[2].phi.clear(); m.blocks[2].w.clear(); });
  variant("NaN phi", [](TsdfUpdate& m) { m.blocks[2].phi[3] = std::numeric_limits<float>::quiet_NaN(); });
  variant("NaN w", [](TsdfUpdate& m) { m.blocks[2].w[3] = std::numeric_limits<float>::quiet_NaN(); });
  variant("negative w", [](TsdfUpdate& m) { m.blocks[2].w[3] = -0.5f; });
  variant("block outside", [](TsdfUpdate& m) { m.blocks[2].y = 100; });
  variant("NaN bounds", [](TsdfUpdate& m) { m.bounds_min.y = std::nan(""); });
  variant("zero voxel size", [](TsdfUpdate& m) { m.voxel_size = 0.0; });

  for (const auto& [name, m] : bad) {
    EXPECT_EQ(mirror.apply(fromMsg(m)), ApplyResult::kMalformed) << name;
    EXPECT_EQ(mirror.map().numBlocks(), 0u) << name;
    EXPECT_FALSE(mirror.synced()) << name;
  }
  EXPECT_EQ(mirror.counters().malformed, bad.size());

  TsdfUpdate other = good;
  other.bounds_max.x = 6.4;
  EXPECT_EQ(mirror.apply(fromMsg(other)), ApplyResult::kIncompatible);
  EXPECT_EQ(mirror.apply(fromMsg(good)), ApplyResult::kApplied) << mirror.lastError();
}
