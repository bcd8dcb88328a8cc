// Seeded random instances and brute force for the tour solver tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "surface_nbv/planning/cost_matrix.h"

namespace surface_nbv {
namespace test {

inline CostMatrix randomAtsp(int n, uint64_t seed, int max_cost = 1000) {
  std::mt19937_64 rng(seed);
  CostMatrix m(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) m.at(i, j) = i == j ? 0.0 : double(rng() % (max_cost + 1));
  }
  return m;
}

inline CostMatrix randomEuclidean(int n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> x(n), y(n);
  for (int i = 0; i < n; ++i) {
    x[i] = double(rng() % 10000) / 10.0;
    y[i] = double(rng() % 10000) / 10.0;
  }
  CostMatrix m(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) m.at(i, j) = std::hypot(x[i] - x[j], y[i] - y[j]);
  }
  return m;
}

// Exhaustive open path from `start` (n <= 9).
inline double bruteForcePath(const CostMatrix& m, int start) {
  std::vector<int> rest;
  for (int i = 0; i < m.size(); ++i) {
    if (i != start) rest.push_back(i);
  }
  double best = 1e300;
  do {
    std::vector<int> path{start};
    path.insert(path.end(), rest.begin(), rest.end());
    best = std::min(best, m.pathCost(path));
  } while (std::next_permutation(rest.begin(), rest.end()));
  return best;
}

inline bool isPermutation(const std::vector<int>& tour, int n) {
  std::vector<int> sorted = tour;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> want(n);
  std::iota(want.begin(), want.end(), 0);
  return sorted == want;
}

}  // namespace test
}  // namespace surface_nbv
