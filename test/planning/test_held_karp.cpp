#include "surface_nbv/planning/held_karp.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tsp_test_helpers.h"

using namespace surface_nbv;

namespace {

double bruteForceTour(const CostMatrix& m) {
  std::vector<int> rest;
  for (int i = 1; i < m.size(); ++i) rest.push_back(i);
  double best = 1e300;
  do {
    std::vector<int> tour{0};
    tour.insert(tour.end(), rest.begin(), rest.end());
    best = std::min(best, m.tourCost(tour));
  } while (std::next_permutation(rest.begin(), rest.end()));
  return best;
}

}  // namespace

TEST(HeldKarp, EqualsBruteForce) {
  for (int n = 1; n <= 9; ++n) {
    for (uint64_t seed = 0; seed < 10; ++seed) {
      const CostMatrix m = test::randomAtsp(n, 100 * n + seed);
      const TourResult r = heldKarp(m);
      ASSERT_EQ(r.status, TspStatus::kExactSolution);
      ASSERT_TRUE(test::isPermutation(r.tour, n));
      EXPECT_EQ(r.tour.front(), 0);
      EXPECT_DOUBLE_EQ(r.cost, m.tourCost(r.tour));
      EXPECT_DOUBLE_EQ(r.cost, bruteForceTour(m)) << "n " << n << " seed " << seed;
    }
  }
}

TEST(HeldKarp, RefusesEmptyTooLargeAndBadCosts) {
  EXPECT_EQ(heldKarp(CostMatrix(0)).status, TspStatus::kEmptyInput);
  const TourResult big = heldKarp(test::randomAtsp(kHeldKarpMaxNodes + 1, 1));
  EXPECT_EQ(big.status, TspStatus::kInvalidInput);
  EXPECT_TRUE(big.tour.empty());
  CostMatrix bad = test::randomAtsp(5, 1);
  bad.at(2, 3) = -1.0;
  EXPECT_EQ(heldKarp(bad).status, TspStatus::kInvalidInput);
}

TEST(HeldKarp, ThirteenNodesPlantedCycle) {
  // Cycle 0 -> 3 -> 6 -> ... (step 3 mod 13) costs 1 per arc, everything else >= 10.
  const int n = 13;
  CostMatrix m = test::randomAtsp(n, 7, 90);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) m.at(i, j) += i == j ? 0.0 : 10.0;
  }
  for (int i = 0; i < n; ++i) m.at(3 * i % n, 3 * (i + 1) % n) = 1.0;
  const TourResult r = heldKarp(m);
  ASSERT_EQ(r.status, TspStatus::kExactSolution);
  EXPECT_DOUBLE_EQ(r.cost, 13.0);
  EXPECT_EQ(r.tour[1], 3);
}
