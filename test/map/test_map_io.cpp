#include "surface_nbv/map/map_io.h"

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace surface_nbv {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;
using Eigen::Vector3i;

constexpr size_t kHeader = 92;
constexpr size_t kBlock = 12 + 512 * 8;

TsdfConfig testConfig(double voxel = 0.1) {
  TsdfConfig c;
  c.voxel_size = voxel;
  c.bounds = AlignedBox(Vector3d(-1.0, -1.0, 0.0), Vector3d(2.2, 2.2, 3.2));
  return c;
}

// phi = clamp(sdf, +-3 voxels), w = 1 for every voxel of the bounds within `band` of the surface.
void writeSdf(TsdfMap* map, const std::function<double(const Vector3d&)>& sdf, double band) {
  const double trunc = 3.0 * map->voxelSize();
  const uint64_t stamp = map->beginChange();
  const Vector3i g = map->gridVoxels();
  for (int z = 0; z < g.z(); ++z) {
    for (int y = 0; y < g.y(); ++y) {
      for (int x = 0; x < g.x(); ++x) {
        const double d = sdf(map->voxelCenter(Vector3i(x, y, z)));
        if (std::abs(d) > band) continue;
        TsdfVoxel* v = map->allocateVoxel(Vector3i(x, y, z));
        v->phi = static_cast<float>(std::clamp(d, -trunc, trunc));
        v->w = 1.0f;
        map->mutableBlock(TsdfMap::blockOfVoxel(Vector3i(x, y, z)))->change_stamp = stamp;
      }
    }
  }
}

void writeSphere(TsdfMap* map, double radius = 0.9) {
  writeSdf(map, [radius](const Vector3d& p) { return (p - Vector3d(0.6, 0.6, 1.6)).norm() - radius; }, 0.3);
}

// Everything a load may touch, to prove a refused load left the map alone.
struct Snapshot {
  uint64_t counter = 0;
  std::vector<std::pair<uint64_t, std::vector<uint8_t>>> blocks;  // stamp, index + voxel bytes

  explicit Snapshot(const TsdfMap& map) : counter(map.changeCounter()) {
    for (const auto& b : map.blocks()) {
      std::vector<uint8_t> bytes(sizeof(b->index) + sizeof(b->voxels));
      std::memcpy(bytes.data(), b->index.data(), sizeof(b->index));
      std::memcpy(bytes.data() + sizeof(b->index), b->voxels.data(), sizeof(b->voxels));
      blocks.emplace_back(b->change_stamp, std::move(bytes));
    }
  }
  bool operator==(const Snapshot& o) const { return counter == o.counter && blocks == o.blocks; }
};

class MapIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("snbv_map_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  static std::vector<uint8_t> readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
  }
  static void writeBytes(const std::string& path, const std::vector<uint8_t>& bytes, size_t size) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(size));
  }
  static void patchByte(const std::string& path, size_t offset, uint8_t value) {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    f.seekp(static_cast<std::streamoff>(offset));
    f.put(static_cast<char>(value));
  }
  static void fixCrc(std::vector<uint8_t>* bytes) {
    const size_t n = bytes->size() - 4;
    const uint32_t crc = static_cast<uint32_t>(crc32(0, bytes->data(), static_cast<uInt>(n)));
    for (int i = 0; i < 4; ++i) (*bytes)[n + i] = static_cast<uint8_t>(crc >> (8 * i));
  }
  // A map of 16 blocks (one plane layer), the target of refused loads.
  static TsdfMap targetMap() {
    TsdfMap map(testConfig());
    writeSdf(&map, [](const Vector3d& p) { return p.z() - 0.35; }, 0.05);
    return map;
  }
  // Loads `path` into target_, expects refusal naming the file and `what`,
  // and target_ as it was built.
  void expectRefused(const std::string& path, const std::string& what) {
    const Status s = loadMap(path, &target_);
    ASSERT_FALSE(s.ok()) << path;
    EXPECT_NE(s.message().find(path), std::string::npos) << s.message();
    EXPECT_NE(s.message().find(what), std::string::npos) << s.message();
    EXPECT_TRUE(Snapshot(target_) == target_before_) << s.message();
  }

  fs::path dir_;
  TsdfMap target_ = targetMap();
  const Snapshot target_before_{target_};
};

TEST_F(MapIoTest, RoundTripIsBitExactWithTheSameBlockSet) {
  TsdfMap map(testConfig());
  writeSphere(&map);
  TsdfVoxel* odd = map.allocateVoxel(Vector3i(0, 0, 0));
  odd->phi = -0.0f;
  odd->w = 1e-40f;  // denormal
  ASSERT_EQ(map.numBlocks(), 33u);  // a 32-block shell and block (0, 0, 0)
  const std::string path = file("sphere.tsdf");
  ASSERT_TRUE(saveMap(map, path).ok());
  EXPECT_EQ(fs::file_size(path), kHeader + 33 * kBlock + 4);

  TsdfMap loaded(testConfig());
  const Status s = loadMap(path, &loaded);
  ASSERT_TRUE(s.ok()) << s.message();
  ASSERT_EQ(loaded.numBlocks(), map.numBlocks());
  for (const auto& b : map.blocks()) {
    const TsdfBlock* c = loaded.block(b->index);
    ASSERT_NE(c, nullptr);
    EXPECT_EQ(std::memcmp(c->voxels.data(), b->voxels.data(), sizeof(b->voxels)), 0);
  }
  EXPECT_TRUE(std::signbit(loaded.voxel(Vector3i(0, 0, 0))->phi));
}

TEST_F(MapIoTest, HeaderLayoutIsLittleEndianAndVersioned) {
  TsdfMap map(testConfig());
  const std::string path = file("empty.tsdf");
  ASSERT_TRUE(saveMap(map, path).ok());
  const std::vector<uint8_t> b = readBytes(path);
  ASSERT_EQ(b.size(), kHeader + 4);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 8), "SNBVTSDF");
  EXPECT_EQ(b[8], 1);
  EXPECT_EQ(b[9] | b[10] | b[11], 0);
  double voxel;
  std::memcpy(&voxel, &b[12], 8);
  EXPECT_EQ(voxel, 0.1);
  EXPECT_EQ(b[20], 8);
  double truncation;
  std::memcpy(&truncation, &b[28], 8);
  EXPECT_DOUBLE_EQ(truncation, 0.3);
  for (int i = 84; i < 92; ++i) EXPECT_EQ(b[i], 0) << i;
}

TEST_F(MapIoTest, LoadReplacesOldBlocksAndStampsLoadedOnesFresh) {
  TsdfMap source(testConfig());
  writeSphere(&source, 0.3);
  const std::string path = file("m.tsdf");
  ASSERT_TRUE(saveMap(source, path).ok());

  TsdfMap map = targetMap();
  for (int i = 0; i < 5; ++i) map.beginChange();
  const uint64_t before = map.changeCounter();
  ASSERT_TRUE(loadMap(path, &map).ok());
  EXPECT_EQ(map.numBlocks(), source.numBlocks());
  EXPECT_GT(map.changeCounter(), before);
  for (const auto& b : map.blocks()) EXPECT_GT(b->change_stamp, before);
  EXPECT_EQ(map.blocksChangedSince(before).size(), source.numBlocks());
  for (const auto& b : source.blocks()) EXPECT_NE(map.block(b->index), nullptr);
  const TsdfMap old = targetMap();
  for (const auto& b : old.blocks()) {
    EXPECT_EQ(map.block(b->index) != nullptr, source.block(b->index) != nullptr);
  }
}

TEST_F(MapIoTest, EmptyFileOfZeroBlocksEmptiesTheMap) {
  const std::string path = file("empty.tsdf");
  ASSERT_TRUE(saveMap(TsdfMap(testConfig()), path).ok());
  TsdfMap map = targetMap();
  ASSERT_GT(map.numBlocks(), 0u);
  ASSERT_TRUE(loadMap(path, &map).ok());
  EXPECT_EQ(map.numBlocks(), 0u);
}

TEST_F(MapIoTest, TruncationAtEveryOffsetOfASmallMapIsRefused) {
  TsdfMap map(testConfig());
  map.allocateVoxel(Vector3i(3, 3, 3))->w = 1.0f;
  map.allocateVoxel(Vector3i(9, 3, 3))->phi = -0.2f;
  const std::string path = file("two.tsdf");
  ASSERT_TRUE(saveMap(map, path).ok());
  const std::vector<uint8_t> bytes = readBytes(path);
  ASSERT_EQ(bytes.size(), kHeader + 2 * kBlock + 4);
  const std::string cut = file("cut.tsdf");
  writeBytes(cut, bytes, bytes.size());
  for (size_t n = bytes.size(); n-- > 0;) {
    fs::resize_file(cut, n);
    expectRefused(cut, n < 8 ? "magic" : "truncated");
    if (HasFailure()) FAIL() << "at length " << n;
  }
}

TEST_F(MapIoTest, TruncationOfALargerMapAtAStrideIsRefused) {
  TsdfMap map(testConfig());
  writeSphere(&map);
  const std::string path = file("sphere.tsdf");
  ASSERT_TRUE(saveMap(map, path).ok());
  const std::vector<uint8_t> bytes = readBytes(path);
  const std::string cut = file("cut.tsdf");
  writeBytes(cut, bytes, bytes.size());
  int tried = 0;
  for (size_t n = bytes.size() - 1; n >= 8; n = n > 997 ? n - 997 : 0, ++tried) {
    fs::resize_file(cut, n);
    expectRefused(cut, "truncated");
  }
  EXPECT_EQ(tried, 132);
}

TEST_F(MapIoTest, EveryFlippedBitOfAOneBlockFileIsRefused) {
  TsdfMap map(testConfig());
  map.allocateVoxel(Vector3i(1, 2, 3))->w = 2.0f;
  const std::string path = file("one.tsdf");
  ASSERT_TRUE(saveMap(map, path).ok());
  const std::vector<uint8_t> good = readBytes(path);
  ASSERT_EQ(good.size(), kHeader + kBlock + 4);
  int checksum_failures = 0;
  for (size_t i = 0; i < good.size(); ++i) {
    patchByte(path, i, static_cast<uint8_t>(good[i] ^ (1u << (i % 8))));
    const Status s = loadMap(path, &target_);
    patchByte(path, i, good[i]);
    ASSERT_FALSE(s.ok()) << "flipped byte " << i;
    ASSERT_TRUE(Snapshot(target_) == target_before_) << "flipped byte " << i;
    checksum_failures += s.message().find("checksum") != std::string::npos;
  }
  EXPECT_TRUE(loadMap(path, &target_).ok());
  // Magic (8), version (4) and the block count (8) fail earlier; everything else on the checksum.
  EXPECT_EQ(checksum_failures, static_cast<int>(good.size()) - 20);
}

TEST_F(MapIoTest, ForeignFilesAreRefused) {
  std::mt19937 rng(7);
  for (size_t n : {0u, 5u, 96u, 5000u}) {
    std::vector<uint8_t> noise(n);
    for (uint8_t& c : noise) c = static_cast<uint8_t>(rng());
    writeBytes(file("noise.bin"), noise, n);
    expectRefused(file("noise.bin"), "magic");
  }
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  writeBytes(file("tri.ply"), std::vector<uint8_t>(ply.begin(), ply.end()), ply.size());
  expectRefused(file("tri.ply"), "magic");
  std::vector<uint8_t> fake(200, 0);
  std::memcpy(fake.data(), "SNBVTSDF", 8);
  fake[8] = 1;
  writeBytes(file("fake.tsdf"), fake, fake.size());
  expectRefused(file("fake.tsdf"), "size mismatch");
  expectRefused(file("missing.tsdf"), "cannot open");
  expectRefused(dir_.string(), "not a regular file");
}

TEST_F(MapIoTest, VersionFromTheFutureIsRefusedEvenWithAValidChecksum) {
  const std::string path = file("v2.tsdf");
  ASSERT_TRUE(saveMap(TsdfMap(testConfig()), path).ok());
  std::vector<uint8_t> b = readBytes(path);
  b[8] = 2;
  fixCrc(&b);
  writeBytes(path, b, b.size());
  expectRefused(path, "format version 2, this build reads version 1");
}

TEST_F(MapIoTest, IncompatibleConfigurationsAreRefused) {
  TsdfMap map(testConfig());
  writeSphere(&map);
  const std::string path = file("sphere.tsdf");
  ASSERT_TRUE(saveMap(map, path).ok());

  TsdfMap coarse(testConfig(0.2));
  const Snapshot before(coarse);
  Status s = loadMap(path, &coarse);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("voxel size 0.100000 m differs from the map's 0.200000 m"), std::string::npos)
      << s.message();
  EXPECT_TRUE(Snapshot(coarse) == before);

  TsdfConfig shifted = testConfig();
  shifted.bounds.min.x() += 0.05;
  TsdfMap shifted_map(shifted);
  s = loadMap(path, &shifted_map);
  EXPECT_NE(s.message().find("bounds min"), std::string::npos) << s.message();

  TsdfConfig small = testConfig();
  small.bounds.max = Vector3d(1.0, 1.0, 1.0);
  TsdfMap small_map(small);
  s = loadMap(path, &small_map);
  EXPECT_NE(s.message().find("outside the map's bounds"), std::string::npos) << s.message();
  EXPECT_EQ(small_map.numBlocks(), 0u);

  TsdfConfig capped = testConfig();
  capped.max_blocks = 31;
  TsdfMap capped_map(capped);
  s = loadMap(path, &capped_map);
  EXPECT_NE(s.message().find("32 blocks exceed the map's max_blocks 31"), std::string::npos) << s.message();

  TsdfConfig wider = testConfig();
  wider.bounds.max = Vector3d(5.0, 5.0, 5.0);
  wider.w_th = 0.7f;
  TsdfMap wider_map(wider);
  s = loadMap(path, &wider_map);
  EXPECT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(wider_map.numBlocks(), 32u);
}

TEST_F(MapIoTest, DuplicateBlocksAndNonFiniteVoxelsAreRefused) {
  TsdfMap map(testConfig());
  map.allocateVoxel(Vector3i(0, 0, 0))->w = 1.0f;
  map.allocateVoxel(Vector3i(8, 0, 0))->w = 1.0f;
  const std::string path = file("two.tsdf");
  ASSERT_TRUE(saveMap(map, path).ok());
  const std::vector<uint8_t> good = readBytes(path);

  std::vector<uint8_t> dup = good;
  std::memcpy(&dup[kHeader + kBlock], &dup[kHeader], 12);
  fixCrc(&dup);
  writeBytes(path, dup, dup.size());
  expectRefused(path, "block (0, 0, 0) appears twice");

  std::vector<uint8_t> nan = good;
  const float bad = std::nanf("");
  std::memcpy(&nan[kHeader + 12 + 8 * 100], &bad, 4);
  fixCrc(&nan);
  writeBytes(path, nan, nan.size());
  expectRefused(path, "non-finite");
}

TEST_F(MapIoTest, SaveReplacesTheFileAndLeavesNoTemporary) {
  TsdfMap map(testConfig());
  writeSphere(&map, 0.3);
  const std::string path = file("m.tsdf");
  writeBytes(path + ".tmp", std::vector<uint8_t>(10, 1), 10);
  ASSERT_TRUE(saveMap(map, path).ok());
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  const uintmax_t first = fs::file_size(path);
  writeSphere(&map, 0.6);
  ASSERT_TRUE(saveMap(map, path).ok());
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  EXPECT_EQ(fs::file_size(path), kHeader + map.numBlocks() * kBlock + 4);
  EXPECT_GT(fs::file_size(path), first);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(MapIoTest, SaveIntoAMissingDirectoryFailsCleanly) {
  const std::string path = file("no/such/dir/m.tsdf");
  const Status s = saveMap(TsdfMap(testConfig()), path);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find(path + ".tmp"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("No such file or directory"), std::string::npos) << s.message();
  EXPECT_TRUE(fs::is_empty(dir_));
  EXPECT_FALSE(saveMap(TsdfMap(testConfig()), "").ok());
}

}  // namespace
}  // namespace surface_nbv
