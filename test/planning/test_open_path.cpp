#include "surface_nbv/planning/open_path.h"

#include <gtest/gtest.h>

#include <numeric>

#include "surface_nbv/surface/viewpoint_utility.h"
#include "tsp_test_helpers.h"

using namespace surface_nbv;

TEST(OpenPath, EqualsBruteForce) {
  for (int n = 1; n <= 9; ++n) {
    for (uint64_t seed = 0; seed < 12; ++seed) {
      const CostMatrix m = test::randomAtsp(n, 555 * n + seed);
      const int start = static_cast<int>(seed % n);
      for (int exact : {12, 0}) {
        LinKernighanSolver::Config c;
        c.seed = seed;
        c.exact_max_nodes = exact;
        const TourResult r = solveOpenPath(m, start, c);
        ASSERT_TRUE(hasTour(r.status));
        ASSERT_TRUE(test::isPermutation(r.tour, n));
        EXPECT_EQ(r.tour.front(), start);
        EXPECT_DOUBLE_EQ(r.cost, m.pathCost(r.tour));
        EXPECT_DOUBLE_EQ(r.cost, test::bruteForcePath(m, start)) << "n " << n << " seed " << seed;
      }
    }
  }
}

TEST(OpenPath, EndIsFreeNotTheCheapestReturn) {
  // The cheapest closed tour 0 1 2 3 differs from the cheapest path from 0 (0 3 2 1).
  CostMatrix m(4, 100.0);
  m.at(0, 1) = m.at(1, 2) = m.at(2, 3) = m.at(3, 0) = 10.0;
  m.at(0, 3) = m.at(3, 2) = m.at(2, 1) = 1.0;
  const TourResult r = solveOpenPath(m, 0);
  EXPECT_EQ(r.tour, (std::vector<int>{0, 3, 2, 1}));
  EXPECT_EQ(r.cost, 3.0);
}

TEST(OpenPath, PerNodeConstantLeavesTheOptimumUnchanged) {
  const CostMatrix m = test::randomAtsp(9, 77);
  CostMatrix shifted = m;
  for (int v = 0; v < 9; ++v) {
    for (int u = 0; u < 9; ++u) shifted.at(u, v) += 17.0 * v;
  }
  const TourResult a = solveOpenPath(m, 4), b = solveOpenPath(shifted, 4);
  EXPECT_DOUBLE_EQ(m.pathCost(b.tour), a.cost);
  EXPECT_NEAR(utilityLogCost(0.5, 2.0, 3.0, 0.1, 0.2, 2.0), 0.1 * 2 + 0.2 * 3 + std::log(4.0), 1e-12);
  EXPECT_NEAR(utilityLogCost(2.0, 0.0, 0.0, 0.1, 0.2, 2.0), 0.0, 1e-12);
}

TEST(OpenPath, DegenerateAndInvalidStarts) {
  EXPECT_EQ(solveOpenPath(CostMatrix(0), 0).status, TspStatus::kEmptyInput);
  const TourResult bad = solveOpenPath(CostMatrix(3, 1.0), 3);
  EXPECT_EQ(bad.status, TspStatus::kInvalidStart);
  EXPECT_FALSE(hasTour(bad.status));
  EXPECT_TRUE(bad.tour.empty());
  EXPECT_EQ(solveOpenPath(CostMatrix(3, 1.0), -1).status, TspStatus::kInvalidStart);
  const TourResult one = solveOpenPath(CostMatrix(1), 0);
  EXPECT_EQ(one.status, TspStatus::kExactSolution);
  EXPECT_EQ(one.tour, std::vector<int>{0});
  EXPECT_EQ(one.cost, 0.0);
  CostMatrix two(2);
  two.at(1, 0) = 5.0;
  two.at(0, 1) = 2.0;
  const TourResult r2 = solveOpenPath(two, 1);
  EXPECT_EQ(r2.tour, (std::vector<int>{1, 0}));
  EXPECT_EQ(r2.cost, 5.0);
}

TEST(OpenPath, FindsAPlantedCheapPathFromTheStart) {
  // A random Hamiltonian path from the start whose arcs cost 1; every other arc
  // costs more than n, so the planted path is the unique optimum.
  for (int n : {40, 200}) {
    std::mt19937_64 rng(n);
    CostMatrix m(n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) m.at(i, j) = i == j ? 0.0 : n + 1.0 + double(rng() % 100);
    }
    std::vector<int> path(n);
    std::iota(path.begin(), path.end(), 0);
    std::shuffle(path.begin(), path.end(), rng);
    for (int i = 0; i + 1 < n; ++i) m.at(path[i], path[i + 1]) = 1.0;
    const TourResult r = solveOpenPath(m, path[0]);
    ASSERT_EQ(r.status, TspStatus::kApproximateSolution);
    EXPECT_EQ(r.tour, path) << "n " << n;
    EXPECT_EQ(r.cost, n - 1.0);
  }
}
