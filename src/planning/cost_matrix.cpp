#include "surface_nbv/planning/cost_matrix.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace surface_nbv {

Status CostMatrix::validate() const {
  for (int i = 0; i < n_; ++i) {
    for (int j = 0; j < n_; ++j) {
      if (i == j) continue;
      const double v = (*this)(i, j);
      const char* what = std::isnan(v)   ? "NaN"
                         : std::isinf(v) ? "infinite"
                         : v < 0         ? "negative"
                         : v > kMaxCost  ? "above kMaxCost"
                                         : nullptr;
      if (what) {
        std::ostringstream ss;
        ss << "cost(" << i << ", " << j << ") = " << v << " is " << what
           << " (costs must be finite, >= 0 and <= " << kMaxCost << "; use a large penalty for unreachable pairs)";
        return Status::Error(ss.str());
      }
    }
  }
  return Status::Ok();
}

bool CostMatrix::isSymmetric() const {
  for (int i = 0; i < n_; ++i) {
    for (int j = i + 1; j < n_; ++j) {
      if ((*this)(i, j) != (*this)(j, i)) return false;
    }
  }
  return true;
}

double CostMatrix::maxOffDiagonal() const {
  double m = 0.0;
  for (int i = 0; i < n_; ++i) {
    for (int j = 0; j < n_; ++j) {
      if (i != j) m = std::max(m, (*this)(i, j));
    }
  }
  return m;
}

double CostMatrix::pathCost(const std::vector<int>& path) const {
  double sum = 0.0;
  for (size_t i = 1; i < path.size(); ++i) sum += (*this)(path[i - 1], path[i]);
  return sum;
}

double CostMatrix::tourCost(const std::vector<int>& tour) const {
  if (tour.size() < 2) return 0.0;
  return pathCost(tour) + (*this)(tour.back(), tour.front());
}

}  // namespace surface_nbv
