// A dense n x n matrix of non-negative arc costs, cost(from, to); asymmetric in
// general. The diagonal is never read by the solvers. A pair with no path is
// given a large finite penalty (kUnreachable is the suggested one): every tour
// stays computable, and a tour that uses such an arc costs more than any that
// does not, as long as penalty > n * (largest real cost). Not thread-safe for writes.
#pragma once

#include <vector>

#include "surface_nbv/util/status.h"

namespace surface_nbv {

class CostMatrix {
 public:
  static constexpr double kUnreachable = 1e9;
  // Costs above this are refused, so that sums over a tour stay exact enough.
  static constexpr double kMaxCost = 1e15;

  CostMatrix() = default;
  explicit CostMatrix(int n, double value = 0.0) : n_(n < 0 ? 0 : n), data_(size_t(n_) * n_, value) {}

  int size() const { return n_; }
  double operator()(int from, int to) const { return data_[size_t(from) * n_ + to]; }
  double& at(int from, int to) { return data_[size_t(from) * n_ + to]; }

  // Refuses NaN, infinite, negative and > kMaxCost entries off the diagonal,
  // naming the first one.
  Status validate() const;
  bool isSymmetric() const;
  double maxOffDiagonal() const;

  // Cost of the closed tour (last -> first included) or of the open path.
  double tourCost(const std::vector<int>& tour) const;
  double pathCost(const std::vector<int>& path) const;

 private:
  int n_ = 0;
  std::vector<double> data_;
};

// The tour cost of moving to cluster v (docs/method.md eq. 5): cost = -log f_uv
//   = lambda_tc * d_kl + lambda_ic * d_lm - log g(v), made non-negative by
// adding log(g_max), g_max >= every g(v) > 0. The added constant is the same
// for every arc into v, so it shifts every tour (each node entered once) and
// every open path from a fixed start (each non-start node entered once) by the
// same amount: the optimal order is unchanged. Minimising it maximises the
// product of the utilities f_uv along the tour.
double utilityToCost(double d_kl, double d_lm, double g_v, double g_max, double lambda_tc, double lambda_ic);

// The tour cost that maximises the sum of the utilities instead:
// kSumCostScale * (1 - f_uv / g_max), in [0, kSumCostScale] for 0 <= f_uv <=
// g_max. Every open path from a fixed start has one arc per non-start node,
// so minimising the sum of these costs maximises the sum of the f_uv. The
// scale keeps the differences between tours far above the rounding of the
// Jonker-Volgenant offsets (jonker_volgenant.h).
constexpr double kSumCostScale = 10.0;
double utilityToSumCost(double f_uv, double g_max);

}  // namespace surface_nbv
