#include "surface_nbv/planning/tour_refine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace surface_nbv;

namespace {

Eigen::Vector4d at(double x, double y, double yaw = 0.0) { return Eigen::Vector4d(x, y, 2.0, yaw); }

std::vector<double> xs(const std::vector<Eigen::Vector4d>& tour) {
  std::vector<double> out;
  for (const Eigen::Vector4d& q : tour) out.push_back(q.x());
  return out;
}

}  // namespace

// Points on a line flown out of order: 2-opt from the start at x = 0 flies
// them in order, carrying each configuration's yaw along.
TEST(TourRefine, UncrossesALineAndKeepsEachConfiguration) {
  std::vector<Eigen::Vector4d> tour = {at(1, 0, 0.1), at(4, 0, 0.4), at(3, 0, 0.3), at(2, 0, 0.2), at(5, 0, 0.5)};
  const Eigen::Vector3d start(0, 0, 2);
  EXPECT_DOUBLE_EQ(openPathLength(start, tour), 1 + 3 + 1 + 1 + 3);
  EXPECT_GT(twoOptOpenPath(start, 0, 20, &tour), 0u);
  EXPECT_EQ(xs(tour), (std::vector<double>{1, 2, 3, 4, 5}));
  for (const Eigen::Vector4d& q : tour) EXPECT_DOUBLE_EQ(q.w(), 0.1 * q.x());
  EXPECT_DOUBLE_EQ(openPathLength(start, tour), 5.0);
  // Nothing left to gain: no move, the tour as it is.
  const std::vector<Eigen::Vector4d> done = tour;
  EXPECT_EQ(twoOptOpenPath(start, 0, 20, &tour), 0u);
  EXPECT_EQ(tour, done);
}

// The current target stays first even where moving it would be shorter; the
// free end lets the last stretch be reversed (one edge replaced).
TEST(TourRefine, KeepsTheFixedHeadAndUsesTheFreeEnd) {
  std::vector<Eigen::Vector4d> tour = {at(5, 0), at(1, 0), at(2, 0), at(3, 0)};
  const Eigen::Vector3d start(0, 0, 2);
  twoOptOpenPath(start, 1, 20, &tour);
  EXPECT_EQ(tour.front(), at(5, 0));
  EXPECT_EQ(xs(tour), (std::vector<double>{5, 3, 2, 1}));  // 5 + 2 + 1 + 1 = 9 against 5 + 4 + 1 + 1 = 11
  std::vector<Eigen::Vector4d> free_head = {at(5, 0), at(1, 0), at(2, 0), at(3, 0)};
  twoOptOpenPath(start, 0, 20, &free_head);
  EXPECT_EQ(xs(free_head), (std::vector<double>{1, 2, 3, 5}));
  // Too short to refine: empty, one or only fixed configurations.
  std::vector<Eigen::Vector4d> empty;
  EXPECT_EQ(twoOptOpenPath(start, 0, 20, &empty), 0u);
  std::vector<Eigen::Vector4d> one = {at(7, 1)};
  EXPECT_EQ(twoOptOpenPath(start, 0, 20, &one), 0u);
  std::vector<Eigen::Vector4d> pinned = {at(5, 0), at(1, 0)};
  EXPECT_EQ(twoOptOpenPath(start, 2, 20, &pinned), 0u);
  EXPECT_EQ(xs(pinned), (std::vector<double>{5, 1}));
}

// Random tours: never longer, a permutation of the same configurations, the
// same result for the same input, and no improving 2-opt move left once the
// passes converge.
TEST(TourRefine, RandomToursGetShorterAndStayPermutations) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-20, 20);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Eigen::Vector4d> tour;
    for (int i = 0; i < 60; ++i) tour.emplace_back(u(rng), u(rng), u(rng), i);
    const Eigen::Vector3d start(u(rng), u(rng), u(rng));
    const size_t fixed = trial % 3;
    const std::vector<Eigen::Vector4d> before = tour;
    std::vector<Eigen::Vector4d> again = tour;
    twoOptOpenPath(start, fixed, 1000, &tour);
    twoOptOpenPath(start, fixed, 1000, &again);
    EXPECT_EQ(tour, again);
    EXPECT_LE(openPathLength(start, tour), openPathLength(start, before) + 1e-9);
    for (size_t k = 0; k < fixed; ++k) EXPECT_EQ(tour[k], before[k]);
    std::vector<double> ids, want;
    for (const Eigen::Vector4d& q : tour) ids.push_back(q.w());
    for (const Eigen::Vector4d& q : before) want.push_back(q.w());
    std::sort(ids.begin(), ids.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(ids, want);
    std::vector<Eigen::Vector4d> settled = tour;
    EXPECT_EQ(twoOptOpenPath(start, fixed, 1, &settled), 0u) << trial;
  }
}
