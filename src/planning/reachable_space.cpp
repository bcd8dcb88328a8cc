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
                          double radius, double slack, double seed_radius, Clear clear) {
  origin_ = bounds.min;
  cells_ = map.gridCells();
  cell_ = map.cellSize();
  filled_ = 0;
  seeded_ = false;
  // kOpen where the cell is clear (one pass over the transform, or a
  // distance query per cell), then the fill turns the connected ones to kFilled.
  static_assert(kOpen == 1, "clearCells marks a clear cell 1");
  if (clear == Clear::kCentreDistance) {
    map.clearCells(radius - slack, &state_);
  } else {
    state_.assign(static_cast<size_t>(cells_.x()) * cells_.y() * cells_.z(), 0);
    for (int x = 0; x < cells_.x(); ++x)
      for (int y = 0; y < cells_.y(); ++y)
        for (int z = 0; z < cells_.z(); ++z) {
          const Eigen::Vector3i c(x, y, z);
          const Eigen::Vector3d centre = origin_ + cell_ * (c.cast<double>().array() + 0.5).matrix();
          if (map.isFree(centre, radius - slack)) state_[index(c)] = kOpen;
        }
  }
  auto open = [&](const Eigen::Vector3i& c) {
    return (c.array() >= 0).all() && (c.array() < cells_.array()).all() && state_[index(c)] == kOpen;
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
            state_[index(c)] = kFilled;
            stack.push_back(c);
          }
        }
  }
  if (stack.empty()) return;
  seeded_ = true;
  for (const Eigen::Vector3i& c : stack) state_[index(c)] = kFilled;
  filled_ = stack.size();
  const int nx = cells_.x(), ny = cells_.y(), nz = cells_.z();
  const ptrdiff_t step_x = static_cast<ptrdiff_t>(ny) * nz, step_y = nz;
  while (!stack.empty()) {
    const Eigen::Vector3i c = stack.back();
    stack.pop_back();
    const ptrdiff_t i = static_cast<ptrdiff_t>(index(c));
    // The six neighbours, each inside the grid and still open.
    const auto visit = [&](bool inside, ptrdiff_t offset, const Eigen::Vector3i& d) {
      if (!inside || state_[i + offset] != kOpen) return;
      state_[i + offset] = kFilled;
      ++filled_;
      stack.push_back(d);
    };
    visit(c.x() + 1 < nx, step_x, c + Eigen::Vector3i(1, 0, 0));
    visit(c.x() > 0, -step_x, c - Eigen::Vector3i(1, 0, 0));
    visit(c.y() + 1 < ny, step_y, c + Eigen::Vector3i(0, 1, 0));
    visit(c.y() > 0, -step_y, c - Eigen::Vector3i(0, 1, 0));
    visit(c.z() + 1 < nz, 1, c + Eigen::Vector3i(0, 0, 1));
    visit(c.z() > 0, -1, c - Eigen::Vector3i(0, 0, 1));
  }
}

bool ReachableSpace::filled(const Eigen::Vector3i& cell) const {
  return (cell.array() >= 0).all() && (cell.array() < cells_.array()).all() && state_[index(cell)] == kFilled;
}

bool ReachableSpace::reachable(const Eigen::Vector3d& p) const {
  if (!seeded_) return true;
  Eigen::Vector3i c;
  if (!cellOf(p, &c)) return false;
  if (state_[index(c)] == kFilled) return true;
  for (int a = 0; a < 3; ++a) {
    for (int s = -1; s <= 1; s += 2) {
      Eigen::Vector3i d = c;
      d[a] += s;
      if (d[a] >= 0 && d[a] < cells_[a] && state_[index(d)] == kFilled) return true;
    }
  }
  return false;
}

}  // namespace surface_nbv
