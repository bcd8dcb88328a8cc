// GridNeighbors against brute force: k nearest and radius queries over
// random points, through adds, removals and grid rebuilds.
#include "surface_nbv/planning/grid_neighbors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace surface_nbv;

namespace {

struct Cloud {
  std::vector<Eigen::Vector3d> points;
  std::vector<bool> present;
};

double dist(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm(); }

// Ids of the present points sorted by distance to q (ties by id: ids are added in order).
std::vector<int> bruteForce(const Cloud& c, const Eigen::Vector3d& q) {
  std::vector<int> ids;
  for (int i = 0; i < static_cast<int>(c.points.size()); ++i)
    if (c.present[i]) ids.push_back(i);
  std::stable_sort(ids.begin(), ids.end(), [&](int a, int b) { return dist(c.points[a], q) < dist(c.points[b], q); });
  return ids;
}

}  // namespace

TEST(GridNeighbors, MatchesBruteForceThroughAddsAndRemovals) {
  Cloud cloud;
  const Eigen::Vector3d lo(-10, -5, 0), hi(20, 15, 6);
  GridNeighbors<int> nn([&](const int& i) { return cloud.points[i]; }, lo, hi);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto randomPoint = [&] {
    return Eigen::Vector3d(lo.x() + u(rng) * (hi.x() - lo.x()), lo.y() + u(rng) * (hi.y() - lo.y()),
                           lo.z() + u(rng) * (hi.z() - lo.z()));
  };
  const double first_cell = nn.cellSize();
  size_t checks = 0;
  for (int round = 0; round < 6; ++round) {
    for (int i = 0; i < 700; ++i) {  // grows by 700, then removes about a third
      cloud.points.push_back(round == 3 && i < 20 ? cloud.points[i] : randomPoint());  // a few exact duplicates
      cloud.present.push_back(true);
      nn.add(static_cast<int>(cloud.points.size()) - 1);
    }
    for (int i = 0; i < static_cast<int>(cloud.points.size()); ++i) {
      if (cloud.present[i] && u(rng) < 0.3) {
        EXPECT_TRUE(nn.remove(i));
        cloud.present[i] = false;
      }
    }
    for (int i = 0; i < static_cast<int>(cloud.present.size()); ++i) {
      if (!cloud.present[i]) {
        EXPECT_FALSE(nn.remove(i)) << "removed twice: " << i;
        break;
      }
    }
    const size_t present = std::count(cloud.present.begin(), cloud.present.end(), true);
    ASSERT_EQ(nn.size(), present);
    for (int q = 0; q < 40; ++q) {
      // Query from stored points too (as the roadmap does) and from the bounds' corner.
      const Eigen::Vector3d p = q == 0 ? lo : q % 2 ? randomPoint() : cloud.points[rng() % cloud.points.size()];
      cloud.points.push_back(p);  // the query element itself, not added
      cloud.present.push_back(false);
      const int query = static_cast<int>(cloud.points.size()) - 1;
      const std::vector<int> truth = bruteForce(cloud, p);
      for (size_t k : {size_t(1), size_t(7), size_t(40), present + 5}) {
        std::vector<int> got;
        nn.nearestK(query, k, got);
        ASSERT_EQ(got.size(), std::min(k, truth.size()));
        for (size_t j = 0; j < got.size(); ++j) {
          ASSERT_DOUBLE_EQ(dist(cloud.points[got[j]], p), dist(cloud.points[truth[j]], p)) << "k " << k << " rank " << j;
        }
        ++checks;
      }
      std::vector<int> within;
      nn.nearestR(query, 2.5, within);
      size_t expected = 0;
      for (int id : truth) expected += dist(cloud.points[id], p) <= 2.5;
      EXPECT_EQ(within.size(), expected);
      EXPECT_TRUE(std::is_sorted(within.begin(), within.end(), [&](int a, int b) {
        return dist(cloud.points[a], p) < dist(cloud.points[b], p);
      }));
      std::vector<int> one;
      nn.nearestK(query, 1, one);
      EXPECT_EQ(nn.nearest(query), one.front());
    }
  }
  EXPECT_GT(checks, 900u);
  EXPECT_LT(nn.cellSize(), first_cell);  // rebuilt finer as it grew
  std::vector<int> all;
  nn.list(all);
  EXPECT_EQ(all.size(), nn.size());
  nn.clear();
  EXPECT_EQ(nn.size(), 0u);
  std::vector<int> none;
  nn.nearestK(0, 5, none);
  EXPECT_TRUE(none.empty());
  EXPECT_THROW(nn.nearest(0), ompl::Exception);
}
