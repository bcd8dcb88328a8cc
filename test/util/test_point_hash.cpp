#include "surface_nbv/util/point_hash.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace surface_nbv
