#include "surface_nbv/map/tsdf_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace surface_nbv;

namespace {

TsdfConfig smallConfig() {
  TsdfConfig c;
  c.voxel_size = 0.5;
  c.bounds = AlignedBox(Eigen::Vector3d(-4, -4, 0), Eigen::Vector3d(4, 4, 4));
  return c;
}

}  // namespace

TEST(TsdfMap, GridCoversBounds) {
  const TsdfMap map(smallConfig());
  EXPECT_EQ(map.gridVoxels(), Eigen::Vector3i(16, 16, 8));
  EXPECT_EQ(map.gridBlocks(), Eigen::Vector3i(2, 2, 1));
}

TEST(TsdfMap, IndexAndCentreRoundTrip) {
  const TsdfMap map(smallConfig());
  Eigen::Vector3i v;
  ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(-4, -4, 0), &v));
  EXPECT_EQ(v, Eigen::Vector3i(0, 0, 0));
  ASSERT_TRUE(map.voxelIndex(Eigen::Vector3d(0.1, -0.1, 3.99), &v));
  EXPECT_EQ(v, Eigen::Vector3i(8, 7, 7));
  EXPECT_TRUE(map.voxelCenter(v).isApprox(Eigen::Vector3d(0.25, -0.25, 3.75)));
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d p = Eigen::Vector3d::Random().cwiseProduct(Eigen::Vector3d(3.9, 3.9, 1.9)) +
                              Eigen::Vector3d(0, 0, 2);
    ASSERT_TRUE(map.voxelIndex(p, &v));
    EXPECT_LE((map.voxelCenter(v) - p).cwiseAbs().maxCoeff(), 0.25 + 1e-12);
  }
}

TEST(TsdfMap, RejectsOutsideAndNonFinite) {
  TsdfMap map(smallConfig());
  Eigen::Vector3i v(7, 7, 7);
  const double inf = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(4.0, 0, 1), Eigen::Vector3d(0, 0, -0.01), Eigen::Vector3d(NAN, 0, 1),
                                   Eigen::Vector3d(0, inf, 1), Eigen::Vector3d(1e30, 0, 1), Eigen::Vector3d(-1e30, 0, 1)}) {
    EXPECT_FALSE(map.voxelIndex(p, &v)) << p.transpose();
  }
  EXPECT_EQ(v, Eigen::Vector3i(7, 7, 7));
  EXPECT_EQ(map.allocateVoxel(Eigen::Vector3i(16, 0, 0)), nullptr);
  EXPECT_EQ(map.allocateVoxel(Eigen::Vector3i(0, -1, 0)), nullptr);
  EXPECT_EQ(map.allocateBlock(Eigen::Vector3i(2, 0, 0)), nullptr);
  EXPECT_EQ(map.allocateBlock(Eigen::Vector3i(std::numeric_limits<int>::min(), 0, 0)), nullptr);
  EXPECT_EQ(map.numBlocks(), 0u);
}

TEST(TsdfMap, StatesFollowWeightThresholdAndSign) {
  TsdfMap map(smallConfig());
  const Eigen::Vector3i a(1, 1, 1), b(2, 1, 1), c(3, 1, 1);
  EXPECT_EQ(map.state(a), VoxelState::kUnknown);
  *map.allocateVoxel(a) = {0.2f, 0.29f};
  *map.allocateVoxel(b) = {0.0f, 0.3f};
  *map.allocateVoxel(c) = {0.01f, 0.3f};
  EXPECT_EQ(map.state(a), VoxelState::kUnknown);
  EXPECT_EQ(map.state(b), VoxelState::kOccupied);
  EXPECT_EQ(map.state(c), VoxelState::kFree);
  EXPECT_EQ(map.state(Eigen::Vector3i(9, 9, 1)), VoxelState::kUnknown);  // unallocated block
  EXPECT_EQ(map.numBlocks(), 1u);
}

TEST(TsdfMap, BlockCapIsCountedNotFatal) {
  TsdfConfig c = smallConfig();
  c.max_blocks = 2;
  TsdfMap map(c);
  EXPECT_NE(map.allocateBlock(Eigen::Vector3i(0, 0, 0)), nullptr);
  EXPECT_NE(map.allocateBlock(Eigen::Vector3i(1, 0, 0)), nullptr);
  EXPECT_EQ(map.allocateBlock(Eigen::Vector3i(0, 1, 0)), nullptr);
  EXPECT_NE(map.allocateBlock(Eigen::Vector3i(1, 0, 0)), nullptr);  // existing blocks still served
  EXPECT_EQ(map.numBlocks(), 2u);
  EXPECT_EQ(map.refusedAllocations(), 1u);
}

TEST(TsdfMap, ChangeStampsListChangedBlocks) {
  TsdfMap map(smallConfig());
  TsdfBlock* b0 = map.allocateBlock(Eigen::Vector3i(0, 0, 0));
  TsdfBlock* b1 = map.allocateBlock(Eigen::Vector3i(1, 1, 0));
  const uint64_t s1 = map.beginChange();
  b0->change_stamp = s1;
  const uint64_t seen = map.changeCounter();
  const uint64_t s2 = map.beginChange();
  b1->change_stamp = s2;
  EXPECT_EQ(map.blocksChangedSince(0).size(), 2u);
  const auto since = map.blocksChangedSince(seen);
  ASSERT_EQ(since.size(), 1u);
  EXPECT_EQ(since[0], Eigen::Vector3i(1, 1, 0));
  map.clear();
  EXPECT_EQ(map.numBlocks(), 0u);
  EXPECT_EQ(map.block(Eigen::Vector3i(0, 0, 0)), nullptr);
}

TEST(TsdfConfig, ValidateNamesBadKeys) {
  auto bad = [](auto edit, const std::string& key) {
    TsdfConfig c = smallConfig();
    edit(c);
    const Status s = c.validate();
    EXPECT_FALSE(s.ok()) << key;
    EXPECT_NE(s.message().find(key), std::string::npos) << s.message();
  };
  bad([](TsdfConfig& c) { c.voxel_size = 0; }, "voxel_size");
  bad([](TsdfConfig& c) { c.voxel_size = NAN; }, "voxel_size");
  bad([](TsdfConfig& c) { c.truncation = 0.1; }, "truncation");
  bad([](TsdfConfig& c) { c.w_th = 0; }, "w_th");
  bad([](TsdfConfig& c) { c.max_weight = 0.1f; }, "max_weight");
  bad([](TsdfConfig& c) { c.bounds.max.x() = -5; }, "bounds");
  bad([](TsdfConfig& c) { c.bounds.max.x() = NAN; }, "bounds");
  bad([](TsdfConfig& c) { c.bounds.max = Eigen::Vector3d::Constant(1e6); }, "block slots");
  bad([](TsdfConfig& c) { c.max_blocks = 0; }, "max_blocks");
  bad([](TsdfConfig& c) { c.threads = 0; }, "threads");
  EXPECT_TRUE(smallConfig().validate().ok());
  EXPECT_DOUBLE_EQ(smallConfig().truncationDistance(), 1.5);
}

TEST(TsdfConfig, InvalidPixelPolicyNames) {
  InvalidPixelPolicy p = InvalidPixelPolicy::kIgnore;
  EXPECT_TRUE(parseInvalidPixelPolicy("clear", &p));
  EXPECT_EQ(p, InvalidPixelPolicy::kClearToMaxRange);
  EXPECT_STREQ(toString(p), "clear");
  EXPECT_FALSE(parseInvalidPixelPolicy("carve", &p));
  EXPECT_EQ(p, InvalidPixelPolicy::kClearToMaxRange);
}
