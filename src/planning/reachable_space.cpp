#include "surface_nbv/planning/reachable_space.h"

#include <cmath>

namespace surface_nbv {

bool ReachableSpace::cellOf(const Eigen::Vector3d& p, Eigen::Vector3i* cell) const {
  if (!p.allFinite()) return false;
  const Eigen::Vector3d q = (p - origin_) / cell_;
  for (int a = 0; a < 3; ++a) {
    const double f = std::floor(q[a]);
    if (f < 0.0 || f >= cells_[a]) return false;
    (*cell)[a] = static_cast<int>(f);
  }
  return true;
}

void ReachableSpace::fill(const CollisionMap& map, const AlignedBox& bounds, const Eigen::Vector3d& from,
                          double radius, double slack, double seed_radius) {
  origin_ = bounds.min;
  cells_ = map.gridCells();
  cell_ = map.cellSize();
  in_.assign(static_cast<size_t>(cells_.prod()), 0);
  filled_ = 0;
  seeded_ = false;
  const double clear = radius - slack;
  auto open = [&](const Eigen::Vector3i& c) {
    return (c.array() >= 0).all() && (c.array() < cells_.array()).all() && in_[index(c)] == 0 &&
           map.cellCentreDistance(c) >= clear;
  };
  std::vector<Eigen::Vector3i> stack;
  Eigen::Vector3i start;
  if (!cellOf(from, &start)) return;
  if (open(start)) {
    stack.push_back(start);
  } else {
    const int n = static_cast<int>(std::ceil(seed_radius / cell_));
    for (int k = -n; k <= n; ++k)
      for (int j = -n; j <= n; ++j)
        for (int i = -n; i <= n; ++i) {
          const Eigen::Vector3i c = start + Eigen::Vector3i(i, j, k);
          if (Eigen::Vector3d(i, j, k).norm() * cell_ <= seed_radius && open(c)) {
            in_[index(c)] = 1;
            stack.push_back(c);
          }
        }
  }
  if (stack.empty()) return;
  seeded_ = true;
  for (const Eigen::Vector3i& c : stack) in_[index(c)] = 1;
  filled_ = stack.size();
  static const Eigen::Vector3i kSteps[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  while (!stack.empty()) {
    const Eigen::Vector3i c = stack.back();
    stack.pop_back();
    for (const Eigen::Vector3i& s : kSteps) {
      const Eigen::Vector3i d = c + s;
      if (!open(d)) continue;
      in_[index(d)] = 1;
      ++filled_;
      stack.push_back(d);
    }
  }
}

bool ReachableSpace::reachable(const Eigen::Vector3d& p) const {
  if (!seeded_) return true;
  Eigen::Vector3i c;
  if (!cellOf(p, &c)) return false;
  if (in_[index(c)]) return true;
  for (int a = 0; a < 3; ++a) {
    for (int s = -1; s <= 1; s += 2) {
      Eigen::Vector3i d = c;
      d[a] += s;
      if (d[a] >= 0 && d[a] < cells_[a] && in_[index(d)]) return true;
    }
  }
  return false;
}

}  // namespace surface_nbv
