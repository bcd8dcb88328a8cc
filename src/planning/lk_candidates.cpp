#include "surface_nbv/planning/lk_candidates.h"

#include <algorithm>
#include <limits>

namespace surface_nbv {
namespace {

// The `count` entries of `others` with the smallest key(x), then cost(x), then index.
template <typename Key, typename Cost>
std::vector<int> smallest(std::vector<int>* others, int count, Key key, Cost cost) {
  const int m = std::min<int>(count, others->size());
  std::partial_sort(others->begin(), others->begin() + m, others->end(), [&](int x, int y) {
    if (key(x) != key(y)) return key(x) < key(y);
    if (cost(x) != cost(y)) return cost(x) < cost(y);
    return x < y;
  });
  return std::vector<int>(others->begin(), others->begin() + m);
}

}  // namespace

std::vector<std::vector<int>> nearestCandidates(const CostMatrix& costs, const std::vector<int>& fixed,
                                                double forbidden, int count) {
  const int n = costs.size();
  std::vector<std::vector<int>> lists(n);
  std::vector<int> others;
  for (int a = 0; a < n; ++a) {
    others.clear();
    for (int b = 0; b < n; ++b) {
      if (b != a && b != fixed[a] && costs(a, b) < forbidden) others.push_back(b);
    }
    const auto cost = [&](int b) { return costs(a, b); };
    lists[a] = smallest(&others, count, cost, cost);
  }
  return lists;
}

std::vector<double> assignmentReducedCosts(const CostMatrix& atsp, double* bound) {
  // Shortest augmenting paths (Hungarian method with potentials), rows and
  // columns 1-based, column 0 a sentinel. Keeps u(i) + v(j) <= c(i, j).
  const int n = atsp.size();
  const double inf = std::numeric_limits<double>::infinity();
  const double big = 4.0 * CostMatrix::kMaxCost;  // stands for the diagonal
  const auto a = [&](int i, int j) { return i == j ? big : atsp(i - 1, j - 1); };
  std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0), min_slack(n + 1);
  std::vector<int> row_of(n + 1, 0), way(n + 1, 0);
  std::vector<char> used(n + 1);
  for (int i = 1; i <= n; ++i) {
    row_of[0] = i;
    int j0 = 0;
    std::fill(min_slack.begin(), min_slack.end(), inf);
    std::fill(used.begin(), used.end(), 0);
    do {
      used[j0] = 1;
      const int i0 = row_of[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= n; ++j) {
        if (used[j]) continue;
        const double slack = a(i0, j) - u[i0] - v[j];
        if (slack < min_slack[j]) {
          min_slack[j] = slack;
          way[j] = j0;
        }
        if (min_slack[j] < delta) {
          delta = min_slack[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= n; ++j) {
        if (used[j]) {
          u[row_of[j]] += delta;
          v[j] -= delta;
        } else {
          min_slack[j] -= delta;
        }
      }
      j0 = j1;
    } while (row_of[j0] != 0);
    do {
      const int j1 = way[j0];
      row_of[j0] = row_of[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  if (bound) *bound = n > 1 ? -v[0] : 0.0;
  std::vector<double> rc(size_t(n) * n, inf);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (i != j) rc[size_t(i) * n + j] = std::max(0.0, atsp(i, j) - u[i + 1] - v[j + 1]);
    }
  }
  return rc;
}

std::vector<std::vector<int>> assignmentCandidates(const CostMatrix& atsp, int count) {
  const int n = atsp.size();
  const std::vector<double> rc = assignmentReducedCosts(atsp);
  std::vector<std::vector<int>> lists(2 * n);
  std::vector<int> others;
  for (int i = 0; i < n; ++i) {
    others.clear();
    for (int j = 0; j < n; ++j) {
      if (j != i) others.push_back(j);
    }
    lists[n + i] = smallest(&others, count, [&](int j) { return rc[size_t(i) * n + j]; },
                            [&](int j) { return atsp(i, j); });
  }
  for (int j = 0; j < n; ++j) {
    others.clear();
    for (int i = 0; i < n; ++i) {
      if (i != j) others.push_back(i);
    }
    lists[j] = smallest(&others, count, [&](int i) { return rc[size_t(i) * n + j]; },
                        [&](int i) { return atsp(i, j); });
    for (int& i : lists[j]) i += n;
  }
  return lists;
}

}  // namespace surface_nbv
