#include "surface_nbv/planning/tour_refine.h"

#include <algorithm>

namespace surface_nbv {

double openPathLength(const Eigen::Vector3d& start, const std::vector<Eigen::Vector4d>& tour) {
  double length = 0.0;
  Eigen::Vector3d prev = start;
  for (const Eigen::Vector4d& q : tour) {
    length += (q.head<3>() - prev).norm();
    prev = q.head<3>();
  }
  return length;
}

size_t twoOptOpenPath(const Eigen::Vector3d& start, size_t fixed, int max_passes, std::vector<Eigen::Vector4d>* tour) {
  constexpr double kGain = 1e-9;
  const size_t n = tour->size();
  // p[0] is the start, p[k] is tour[k - 1]; p[1 .. fixed] stay in place.
  std::vector<Eigen::Vector3d> p;
  p.reserve(n + 1);
  p.push_back(start);
  for (const Eigen::Vector4d& q : *tour) p.push_back(q.head<3>());
  std::vector<size_t> order(n);
  for (size_t k = 0; k < n; ++k) order[k] = k;
  const auto d = [&p](size_t a, size_t b) { return (p[a] - p[b]).norm(); };
  size_t moves = 0;
  for (int pass = 0; pass < max_passes; ++pass) {
    bool improved = false;
    for (size_t i = fixed + 1; i < n; ++i) {
      for (size_t j = i + 1; j <= n; ++j) {
        double delta = d(i - 1, j) - d(i - 1, i);
        if (j < n) delta += d(i, j + 1) - d(j, j + 1);
        if (delta < -kGain) {
          std::reverse(p.begin() + static_cast<long>(i), p.begin() + static_cast<long>(j) + 1);
          std::reverse(order.begin() + static_cast<long>(i) - 1, order.begin() + static_cast<long>(j));
          ++moves;
          improved = true;
        }
      }
    }
    if (!improved) break;
  }
  if (moves > 0) {
    std::vector<Eigen::Vector4d> refined;
    refined.reserve(n);
    for (size_t k : order) refined.push_back((*tour)[k]);
    *tour = std::move(refined);
  }
  return moves;
}

}  // namespace surface_nbv
