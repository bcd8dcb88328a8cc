#include "surface_nbv/util/point_hash.h"
#include "surface_nbv/util/bits_hash.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <set>

namespace surface_nbv {
namespace {

TEST(PointHash, AnyFindsThePointsWithinTheRadiusAcrossCells) {
  PointHash hash(1.0);
  hash.add(Eigen::Vector3d(0.95, 0.0, 0.0), 0);   // in the cell next to the query's
  hash.add(Eigen::Vector3d(3.0, 0.0, 0.0), 1);
  std::vector<int> found;
  EXPECT_TRUE(hash.any(Eigen::Vector3d(1.05, 0.0, 0.0), 0.5, [&](int id) {
    found.push_back(id);
    return true;
  }));
  EXPECT_EQ(found, std::vector<int>{0});
  EXPECT_FALSE(hash.any(Eigen::Vector3d(2.0, 0.0, 0.0), 0.9, [](int) { return true; }));
}

TEST(PointHash, NearestIsTheClosestWithinTheRadiusAndTheLastOfEquallyNearOnes) {
  PointHash hash(1.0);
  hash.add(Eigen::Vector3d(0.0, 0.0, 0.0), 0);
  hash.add(Eigen::Vector3d(0.6, 0.0, 0.0), 1);
  hash.add(Eigen::Vector3d(-0.6, 0.0, 0.0), 2);
  EXPECT_EQ(hash.nearest(Eigen::Vector3d(0.5, 0.0, 0.0), 1.0), 1);
  EXPECT_EQ(hash.nearest(Eigen::Vector3d(0.1, 0.0, 0.0), 1.0), 0);
  // 0.3 from 0, 0.67 from 1 and 2.
  EXPECT_EQ(hash.nearest(Eigen::Vector3d(0.0, 0.3, 0.0), 1.0), 0);
  EXPECT_EQ(hash.nearest(Eigen::Vector3d(0.3, 0.0, 0.0), 1.0), 1) << "0 and 1 are 0.3 away: the later one";
  EXPECT_EQ(hash.nearest(Eigen::Vector3d(0.0, 0.0, 5.0), 1.0), -1);
  EXPECT_EQ(hash.nearest(Eigen::Vector3d(1.5, 0.0, 0.0), 0.8), -1) << "0.9 from the nearest";
  hash.clear();
  EXPECT_EQ(hash.nearest(Eigen::Vector3d(0.0, 0.0, 0.0), 1.0), -1);
}

// hashBits keys caches by the exact bits: equal words hash equal, and the
// word order, a sign or the last bit of a mantissa changes the hash.
TEST(BitsHash, EqualBitsHashEqualAndNeighbouringKeysApart) {
  const auto bitsOf = [](double x, double y, double z) {
    const double v[3] = {x, y, z};
    std::array<uint64_t, 3> b{};
    std::memcpy(b.data(), v, sizeof(v));
    return b;
  };
  const auto h = [](const std::array<uint64_t, 3>& b) { return hashBits(b.data(), b.size()); };
  EXPECT_EQ(h(bitsOf(1.5, -2.0, 3.25)), h(bitsOf(1.5, -2.0, 3.25)));
  std::set<size_t> seen;
  const double next = std::nextafter(1.5, 2.0);
  for (const auto& b : {bitsOf(1.5, -2.0, 3.25), bitsOf(-2.0, 1.5, 3.25), bitsOf(-1.5, -2.0, 3.25),
                        bitsOf(next, -2.0, 3.25), bitsOf(0.0, 0.0, 0.0), bitsOf(-0.0, 0.0, 0.0)}) {
    seen.insert(h(b));
  }
  EXPECT_EQ(seen.size(), 6u);
  EXPECT_NE(hashBits(nullptr, 0), h(bitsOf(0.0, 0.0, 0.0)));
}

TEST(BitsKey, KeysAreTheExactBitsWithAnOrderAndTheirHash) {
  const double a[4] = {1.5, -2.0, 3.25, 0.5}, same[4] = {1.5, -2.0, 3.25, 0.5};
  const double next[4] = {1.5, -2.0, 3.25, std::nextafter(0.5, 1.0)};
  const double zero[4] = {0.0, 0.0, 0.0, 0.0}, minus_zero[4] = {-0.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(BitsKey<4>(a), BitsKey<4>(same));
  EXPECT_FALSE(BitsKey<4>(a) == BitsKey<4>(next));
  // 0 == -0 as doubles, but they are two keys: a cache never merges them.
  EXPECT_FALSE(BitsKey<4>(zero) == BitsKey<4>(minus_zero));
  // A strict order: exactly one of a < b, b < a for different keys.
  EXPECT_NE(BitsKey<4>(a) < BitsKey<4>(next), BitsKey<4>(next) < BitsKey<4>(a));
  EXPECT_FALSE(BitsKey<4>(a) < BitsKey<4>(same));
  EXPECT_FALSE(BitsKey<4>(same) < BitsKey<4>(a));
  const BitsKey<4> k(a);
  EXPECT_EQ(BitsKeyHash<4>()(k), hashBits(k.bits.data(), 4));
  EXPECT_NE(BitsKeyHash<4>()(BitsKey<4>(zero)), BitsKeyHash<4>()(BitsKey<4>(minus_zero)));
  // The first three words of a 4-key are the 3-key of the same values.
  EXPECT_EQ(BitsKey<3>(a).bits[2], k.bits[2]);
}
}  // namespace
}  // namespace surface_nbv
