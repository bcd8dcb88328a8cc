#include "surface_nbv/planning/held_karp.h"

#include <chrono>
#include <limits>

namespace surface_nbv {

TourResult heldKarp(const CostMatrix& costs) {
  const auto t0 = std::chrono::steady_clock::now();
  TourResult r;
  const int n = costs.size();
  if (refuseInput(costs.validate(), n, &r)) return r;
  if (n > kHeldKarpMaxNodes) {
    r.message = "Held-Karp takes at most " + std::to_string(kHeldKarpMaxNodes) + " nodes, got " + std::to_string(n);
    return r;
  }
  r.status = TspStatus::kExactSolution;
  if (n <= 2) {
    for (int i = 0; i < n; ++i) r.tour.push_back(i);
    r.cost = costs.tourCost(r.tour);
    return r;
  }
  // dp[mask][j]: cheapest path from 0 through the nodes of mask (over 1..n-1), ending at j in mask.
  const int m = n - 1;
  const size_t masks = size_t(1) << m;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dp(masks * m, inf);
  std::vector<signed char> parent(masks * m, -1);
  for (int j = 0; j < m; ++j) dp[(size_t(1) << j) * m + j] = costs(0, j + 1);
  for (size_t mask = 1; mask < masks; ++mask) {
    for (int j = 0; j < m; ++j) {
      const double base = dp[mask * m + j];
      if (!(mask >> j & 1) || base == inf) continue;
      for (int k = 0; k < m; ++k) {
        if (mask >> k & 1) continue;
        const size_t next = (mask | (size_t(1) << k)) * m + k;
        const double v = base + costs(j + 1, k + 1);
        if (v < dp[next]) {
          dp[next] = v;
          parent[next] = static_cast<signed char>(j);
        }
      }
    }
  }
  const size_t full = masks - 1;
  int last = 0;
  double best = inf;
  for (int j = 0; j < m; ++j) {
    const double v = dp[full * m + j] + costs(j + 1, 0);
    if (v < best) {
      best = v;
      last = j;
    }
  }
  std::vector<int> reversed;
  size_t mask = full;
  for (int j = last; j >= 0;) {
    reversed.push_back(j + 1);
    const int p = parent[mask * m + j];
    mask &= ~(size_t(1) << j);
    j = p;
  }
  r.tour.push_back(0);
  r.tour.insert(r.tour.end(), reversed.rbegin(), reversed.rend());
  r.cost = costs.tourCost(r.tour);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace surface_nbv
