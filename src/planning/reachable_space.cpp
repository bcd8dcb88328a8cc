#include "surface_nbv/planning/reachable_space.h"

#include <algorithm>
#include <cmath>
#include <deque>

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
  // Breadth first, so that each filled cell keeps the direction to the
  // neighbour it was reached from on a shortest 6-connected way (corridor()).
  // The queue holds cell indices: only the front of the fill at a time.
  std::deque<size_t> queue;
  Eigen::Vector3i start;
  if (!cellOf(from, &start)) return;
  if (open(start)) {
    queue.push_back(index(start));
  } else {
    const int n = static_cast<int>(std::ceil(seed_radius / cell_));
    for (int k = -n; k <= n; ++k)
      for (int j = -n; j <= n; ++j)
        for (int i = -n; i <= n; ++i) {
          const Eigen::Vector3i c = start + Eigen::Vector3i(i, j, k);
          if (Eigen::Vector3d(i, j, k).norm() * cell_ <= seed_radius && open(c)) {
            state_[index(c)] = kSeed;
            queue.push_back(index(c));
          }
        }
  }
  if (queue.empty()) return;
  seeded_ = true;
  for (size_t i : queue) state_[i] = kSeed;
  filled_ = queue.size();
  const size_t nz = static_cast<size_t>(cells_.z()), nyz = static_cast<size_t>(cells_.y()) * nz;
  const size_t nx = static_cast<size_t>(cells_.x()), ny = static_cast<size_t>(cells_.y());
  while (!queue.empty()) {
    const size_t i = queue.front();
    queue.pop_front();
    const size_t x = i / nyz, y = (i / nz) % ny, z = i % nz;
    // The six neighbours, each inside the grid and still open; `back` is
    // the direction from the neighbour to this cell.
    const auto visit = [&](bool inside, size_t j, uint8_t back) {
      if (!inside || state_[j] != kOpen) return;
      state_[j] = static_cast<uint8_t>(kFilled + back);
      ++filled_;
      queue.push_back(j);
    };
    visit(x + 1 < nx, i + nyz, 1);
    visit(x > 0, i - nyz, 0);
    visit(y + 1 < ny, i + nz, 3);
    visit(y > 0, i - nz, 2);
    visit(z + 1 < nz, i + 1, 5);
    visit(z > 0, i - 1, 4);
  }
}

bool ReachableSpace::filled(const Eigen::Vector3i& cell) const {
  return (cell.array() >= 0).all() && (cell.array() < cells_.array()).all() && state_[index(cell)] >= kFilled;
}

bool ReachableSpace::filledAt(const Eigen::Vector3d& p, Eigen::Vector3i* cell) const {
  if (!cellOf(p, cell)) return false;
  if (state_[index(*cell)] >= kFilled) return true;
  for (int a = 0; a < 3; ++a) {
    for (int s = -1; s <= 1; s += 2) {
      Eigen::Vector3i d = *cell;
      d[a] += s;
      if (d[a] >= 0 && d[a] < cells_[a] && state_[index(d)] >= kFilled) {
        *cell = d;
        return true;
      }
    }
  }
  return false;
}

bool ReachableSpace::reachable(const Eigen::Vector3d& p) const {
  Eigen::Vector3i c;
  return !seeded_ || filledAt(p, &c);
}

bool ReachableSpace::corridor(const Eigen::Vector3d& to, std::vector<Eigen::Vector3d>* points) const {
  points->clear();
  Eigen::Vector3i c;
  if (!seeded_ || !filledAt(to, &c)) return false;
  // Back along the directions the fill stored, to a seed; each step is one
  // cell closer to it, so this ends.
  static const int kStep[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (;;) {
    points->push_back(origin_ + cell_ * (c.cast<double>().array() + 0.5).matrix());
    const uint8_t s = state_[index(c)];
    if (s == kSeed) break;
    const int dir = s - kFilled;
    c += Eigen::Vector3i(kStep[dir][0], kStep[dir][1], kStep[dir][2]);
  }
  std::reverse(points->begin(), points->end());
  return true;
}

}  // namespace surface_nbv
