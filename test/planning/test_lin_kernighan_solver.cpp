#include "surface_nbv/planning/lin_kernighan_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "surface_nbv/planning/held_karp.h"
#include "surface_nbv/planning/lk_candidates.h"
#include "tsp_test_helpers.h"

using namespace surface_nbv;

namespace {

LinKernighanSolver::Config lkOnly(uint64_t seed) {
  LinKernighanSolver::Config c;
  c.seed = seed;
  c.exact_max_nodes = 0;  // LK itself, not Held-Karp
  return c;
}

// First-improvement asymmetric 2-opt (segment reversal, costs recomputed) from a random tour.
double twoOptRun(const CostMatrix& m, std::mt19937_64* rng) {
  const int n = m.size();
  std::vector<int> t(n);
  std::iota(t.begin(), t.end(), 0);
  std::shuffle(t.begin(), t.end(), *rng);
  double cost = m.tourCost(t);
  for (bool improved = true; improved;) {
    improved = false;
    for (int i = 0; i + 2 < n; ++i) {
      for (int j = i + 2; j < n; ++j) {
        std::reverse(t.begin() + i + 1, t.begin() + j + 1);
        const double c = m.tourCost(t);
        if (c < cost - 1e-9) {
          cost = c;
          improved = true;
        } else {
          std::reverse(t.begin() + i + 1, t.begin() + j + 1);
        }
      }
    }
  }
  return cost;
}

}  // namespace

TEST(LinKernighan, BeatsTheBestOfManyTwoOptRunsAt100Nodes) {
  const CostMatrix m = test::randomAtsp(100, 2121);
  std::mt19937_64 rng(5);
  double best_2opt = 1e300;
  for (int run = 0; run < 20; ++run) best_2opt = std::min(best_2opt, twoOptRun(m, &rng));
  const TourResult lk = LinKernighanSolver().solve(m);
  ASSERT_EQ(lk.status, TspStatus::kApproximateSolution);
  ASSERT_TRUE(test::isPermutation(lk.tour, 100));
  EXPECT_LT(lk.cost, 0.5 * best_2opt);
  double bound = 0.0;
  assignmentReducedCosts(m, &bound);
  EXPECT_GE(lk.cost, bound - 1e-9);
  EXPECT_LE(lk.cost, 1.02 * bound) << "assignment bound " << bound;
}

TEST(LinKernighan, AssignmentCandidatesHoldTheOptimalAssignment) {
  // A planted cycle cover of cost 0, every other arc costing at least 1: its
  // arcs have reduced cost 0 and come first in both lists of their ends.
  const int n = 30;
  CostMatrix m = test::randomAtsp(n, 17);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) m.at(i, j) += 1.0;
    m.at(i, (i + 7) % n) = 0.0;
  }
  double bound = -1.0;
  const std::vector<double> rc = assignmentReducedCosts(m, &bound);
  EXPECT_DOUBLE_EQ(bound, 0.0);
  const auto lists = assignmentCandidates(m, 5);
  ASSERT_EQ(static_cast<int>(lists.size()), 2 * n);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 7) % n;
    EXPECT_DOUBLE_EQ(rc[size_t(i) * n + j], 0.0);
    ASSERT_EQ(lists[n + i].size(), 5u);
    EXPECT_EQ(lists[n + i][0], j);
    EXPECT_EQ(lists[j][0], n + i);
    for (int k : lists[n + i]) EXPECT_LT(k, n);
    for (int k : lists[i]) EXPECT_GE(k, n);
  }
}

TEST(LinKernighan, EqualsHeldKarpOnRandomAsymmetricInstances) {
  int instances = 0;
  for (int n = 2; n <= 12; ++n) {
    for (uint64_t seed = 0; seed < 40; ++seed, ++instances) {
      const CostMatrix m = test::randomAtsp(n, 7919 * n + seed, seed % 2 ? 1000 : 10);
      const TourResult exact = heldKarp(m);
      const TourResult lk = LinKernighanSolver(lkOnly(seed)).solve(m);
      ASSERT_TRUE(hasTour(lk.status)) << toString(lk.status);
      ASSERT_TRUE(test::isPermutation(lk.tour, n));
      EXPECT_EQ(lk.tour.front(), 0);
      EXPECT_DOUBLE_EQ(lk.cost, m.tourCost(lk.tour));
      EXPECT_DOUBLE_EQ(lk.cost, exact.cost) << "n " << n << " seed " << seed;
      EXPECT_EQ(lk.status, n <= 4 ? TspStatus::kExactSolution : TspStatus::kApproximateSolution);
    }
  }
  EXPECT_EQ(instances, 440);
}

TEST(LinKernighan, EqualsHeldKarpOnSymmetricInstances) {
  for (int n = 4; n <= 12; ++n) {
    for (uint64_t seed = 0; seed < 10; ++seed) {
      const CostMatrix m = test::randomEuclidean(n, 31 * n + seed);
      EXPECT_NEAR(LinKernighanSolver(lkOnly(seed)).solve(m).cost, heldKarp(m).cost, 1e-6) << "n " << n;
    }
  }
}

TEST(LinKernighan, SmallInstancesAreSolvedExactlyByDefault) {
  const CostMatrix m = test::randomAtsp(12, 5);
  const TourResult r = LinKernighanSolver().solve(m);
  EXPECT_EQ(r.status, TspStatus::kExactSolution);
  EXPECT_DOUBLE_EQ(r.cost, heldKarp(m).cost);
}

TEST(LinKernighan, DegenerateInputs) {
  const LinKernighanSolver solver(lkOnly(1));
  const TourResult empty = solver.solve(CostMatrix(0));
  EXPECT_EQ(empty.status, TspStatus::kEmptyInput);
  EXPECT_FALSE(hasTour(empty.status));
  EXPECT_TRUE(empty.tour.empty());

  const TourResult one = solver.solve(CostMatrix(1, 5.0));
  EXPECT_EQ(one.status, TspStatus::kExactSolution);
  EXPECT_EQ(one.tour, std::vector<int>{0});
  EXPECT_EQ(one.cost, 0.0);

  CostMatrix two(2);
  two.at(0, 1) = 3;
  two.at(1, 0) = 4;
  const TourResult r2 = solver.solve(two);
  EXPECT_EQ(r2.status, TspStatus::kExactSolution);
  EXPECT_EQ(r2.tour, (std::vector<int>{0, 1}));
  EXPECT_EQ(r2.cost, 7.0);

  CostMatrix three(3, 10.0);
  three.at(0, 2) = three.at(2, 1) = three.at(1, 0) = 1.0;
  const TourResult r3 = solver.solve(three);
  EXPECT_EQ(r3.status, TspStatus::kExactSolution);
  EXPECT_EQ(r3.tour, (std::vector<int>{0, 2, 1}));
  EXPECT_EQ(r3.cost, 3.0);
}

TEST(LinKernighan, RefusesBadCostsAndConfig) {
  for (double bad : {std::nan(""), -1.0, double(INFINITY), 2 * CostMatrix::kMaxCost}) {
    CostMatrix m = test::randomAtsp(20, 1);
    m.at(3, 4) = bad;
    const TourResult r = LinKernighanSolver().solve(m);
    EXPECT_EQ(r.status, TspStatus::kInvalidInput) << bad;
    EXPECT_TRUE(r.tour.empty());
    EXPECT_NE(r.message.find("cost(3, 4)"), std::string::npos) << r.message;
  }
  LinKernighanSolver::Config c;
  c.max_depth = 2;
  const TourResult r = LinKernighanSolver(c).solve(test::randomAtsp(20, 1));
  EXPECT_EQ(r.status, TspStatus::kInvalidInput);
  EXPECT_NE(r.message.find("max_depth"), std::string::npos);
}

TEST(LinKernighan, PointsOnACircleGiveThePolygon) {
  for (int n : {5, 17, 60, 150}) {
    CostMatrix m(n);
    const double radius = 1000.0;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const double a = 2 * M_PI * i / n, b = 2 * M_PI * j / n;
        m.at(i, j) = std::hypot(radius * (std::cos(a) - std::cos(b)), radius * (std::sin(a) - std::sin(b)));
      }
    }
    const double polygon = n * 2 * radius * std::sin(M_PI / n);
    const TourResult r = LinKernighanSolver(lkOnly(3)).solve(m);
    EXPECT_NEAR(r.cost, polygon, 1e-6 * polygon) << "n " << n;
  }
}

TEST(LinKernighan, FindsAPlantedCheapCycle) {
  // Arcs of a random Hamiltonian cycle cost 1..3; every other arc costs more than 3 n,
  // so any other tour costs more than the planted one.
  for (int n : {30, 100, 300}) {
    std::mt19937_64 rng(n);
    CostMatrix m(n);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) m.at(i, j) = i == j ? 0.0 : 3.0 * n + 1.0 + double(rng() % 100);
    }
    std::vector<int> cycle(n);
    std::iota(cycle.begin(), cycle.end(), 0);
    std::shuffle(cycle.begin(), cycle.end(), rng);
    double planted = 0.0;
    for (int i = 0; i < n; ++i) {
      const double c = 1.0 + double(rng() % 3);
      m.at(cycle[i], cycle[(i + 1) % n]) = c;
      planted += c;
    }
    const TourResult r = LinKernighanSolver(lkOnly(1)).solve(m);
    EXPECT_DOUBLE_EQ(r.cost, planted) << "n " << n;
  }
}

TEST(LinKernighan, RepeatsExactlyWithASeed) {
  const CostMatrix m = test::randomAtsp(120, 42);
  const TourResult a = LinKernighanSolver(lkOnly(9)).solve(m);
  const TourResult b = LinKernighanSolver(lkOnly(9)).solve(m);
  EXPECT_EQ(a.tour, b.tour);
  EXPECT_EQ(a.trials, b.trials);
  EXPECT_EQ(a.trials, 4 * 120 - 100);
  LinKernighanSolver::Config c = lkOnly(9);
  c.max_trials = 0;
  const TourResult no_kicks = LinKernighanSolver(c).solve(m);
  EXPECT_EQ(no_kicks.trials, 0);
  EXPECT_GE(no_kicks.cost, a.cost);
}

TEST(LinKernighan, TimeLimitGivesAValidTour) {
  LinKernighanSolver::Config c = lkOnly(1);
  c.time_limit_s = 1e-4;
  c.max_trials = 1000000;
  const CostMatrix m = test::randomAtsp(300, 3);
  const TourResult r = LinKernighanSolver(c).solve(m);
  EXPECT_EQ(r.status, TspStatus::kTimeout);
  ASSERT_TRUE(test::isPermutation(r.tour, 300));
  EXPECT_DOUBLE_EQ(r.cost, m.tourCost(r.tour));
}
