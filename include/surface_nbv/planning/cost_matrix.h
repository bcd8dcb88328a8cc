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

}  // namespace surface_nbv
