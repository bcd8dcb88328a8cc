#include "surface_nbv/surface/point_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

using namespace surface_nbv;

TEST(PointGrid, QueriesFindEveryPointWithinTheRadius) {
  std::mt19937 rng(41);
  for (double extent : {10.0, 1000.0}) {  // 1000 m at 2 m: more than the cell cap per axis
    std::uniform_real_distribution<double> u(0.0, extent);
    std::vector<Eigen::Vector3d> points(3000);
    AlignedBox box;
    for (Eigen::Vector3d& p : points) {
      p = Eigen::Vector3d(u(rng), u(rng), 0.1 * u(rng));
      box.extend(p);
    }
    const double radius = 2.0;
    PointGrid grid(box, radius, points.size());
    for (size_t i = 0; i < points.size(); ++i) grid.insert(static_cast<int>(i), points[i]);
    size_t close_pairs = 0;
    for (int trial = 0; trial < 300; ++trial) {
      // Queries near a point, and anywhere up to 5 m outside the box.
      std::uniform_real_distribution<double> offset(-1.0, 1.0);
      const Eigen::Vector3d q = trial % 2 ? Eigen::Vector3d(points[rng() % points.size()] +
                                                            Eigen::Vector3d(offset(rng), offset(rng), offset(rng)))
                                          : Eigen::Vector3d(u(rng) * 1.01 - 5.0, u(rng) * 1.01 - 5.0, 0.1 * u(rng));
      std::vector<int> found;
      grid.forEachNear(q, [&](int id) { found.push_back(id); });
      std::sort(found.begin(), found.end());
      EXPECT_TRUE(std::adjacent_find(found.begin(), found.end()) == found.end()) << "an id reported twice";
      for (size_t i = 0; i < points.size(); ++i) {
        if ((points[i] - q).norm() >= radius) continue;
        ++close_pairs;
        EXPECT_TRUE(std::binary_search(found.begin(), found.end(), static_cast<int>(i)));
      }
    }
    EXPECT_GT(close_pairs, 100u);
  }
}

TEST(PointGrid, EmptyBoxHoldsPointsAnywhere) {
  PointGrid grid(AlignedBox(), 1.0, 2);
  grid.insert(0, Eigen::Vector3d(3, 4, 5));
  grid.insert(1, Eigen::Vector3d(-3, 4, 5));
  int count = 0;
  grid.forEachNear(Eigen::Vector3d(3, 4, 5), [&](int) { ++count; });
  EXPECT_EQ(count, 2);
}
