#include "surface_nbv/eval/free_space_grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {

double squaredDistanceToTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return ap.squaredNorm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return bp.squaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return (p - (a + d1 / (d1 - d3) * ab)).squaredNorm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return cp.squaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return (p - (a + d2 / (d2 - d6) * ac)).squaredNorm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).squaredNorm();
  }
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).squaredNorm();
}

Status FreeSpaceGrid::build(const TriangleMesh& mesh, const AlignedBox& bounds, double cell, double collision_radius,
                            int threads) {
  if (bounds.empty() || !bounds.min.allFinite() || !bounds.max.allFinite()) {
    return Status::Error("bounds expected finite and non-empty");
  }
  if (!(cell > 0.0)) return Status::Error("free_space_cell expected > 0");
  const Eigen::Array3d cells = (bounds.size() / cell).array().ceil().max(1.0);
  if (cells.prod() > 64e6) {
    return Status::Error("bounds hold " + std::to_string(static_cast<long long>(cells.prod())) +
                         " free-space cells (limit 64M): shrink the bounds or grow free_space_cell");
  }
  bounds_ = bounds;
  cell_ = cell;
  dims_ = cells.cast<int>().matrix();
  state_.assign(static_cast<size_t>(cells.prod()), kFree);
  markBlocked(mesh, collision_radius, threads);
  floodFromOutside();
  measureClearance();
  return Status::Ok();
}

bool FreeSpaceGrid::cellOf(const Eigen::Vector3d& p, Eigen::Vector3i* cell) const {
  const Eigen::Vector3d f = (p - bounds_.min) / cell_;
  if (!(f.array() >= 0.0).all() || !(f.array() < dims_.cast<double>().array()).all()) return false;
  *cell = f.array().floor().cast<int>();
  return true;
}

bool FreeSpaceGrid::reachable(const Eigen::Vector3d& p) const { return cellsToReachable(p) == 0; }

int FreeSpaceGrid::cellsToReachable(const Eigen::Vector3d& p) const {
  Eigen::Vector3i c;
  return cellOf(p, &c) ? clearance_[linear(c.x(), c.y(), c.z())] : -1;
}

// A cell is blocked when its centre lies within collision_radius of a
// triangle. Each z layer is one task (writes stay disjoint); per layer, only
// the triangles whose grown box spans the layer's centre are tested.
void FreeSpaceGrid::markBlocked(const TriangleMesh& mesh, double collision_radius, int threads) {
  const double r = collision_radius, r2 = r * r;
  std::vector<AlignedBox> boxes(mesh.triangles.size());
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) boxes[i].extend(mesh.vertices[mesh.triangles[i][k]].cast<double>());
    boxes[i].min.array() -= r;
    boxes[i].max.array() += r;
  }
  std::vector<size_t> blocked(dims_.z(), 0);
  parallelFor(static_cast<size_t>(dims_.z()), threads, [&](size_t layer) {
    const int z = static_cast<int>(layer);
    const double cz = bounds_.min.z() + (z + 0.5) * cell_;
    for (size_t i = 0; i < boxes.size(); ++i) {
      const AlignedBox& box = boxes[i];
      if (cz < box.min.z() || cz > box.max.z() || !box.min.allFinite() || !box.max.allFinite()) continue;
      const Eigen::Vector3i& t = mesh.triangles[i];
      const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>();
      const Eigen::Vector3d b = mesh.vertices[t[1]].cast<double>();
      const Eigen::Vector3d c = mesh.vertices[t[2]].cast<double>();
      const Eigen::Vector2d lo = ((box.min - bounds_.min) / cell_ - Eigen::Vector3d::Constant(0.5)).head<2>();
      const Eigen::Vector2d hi = ((box.max - bounds_.min) / cell_ - Eigen::Vector3d::Constant(0.5)).head<2>();
      const int x0 = static_cast<int>(std::ceil(std::clamp(lo.x(), 0.0, double(dims_.x()))));
      const int y0 = static_cast<int>(std::ceil(std::clamp(lo.y(), 0.0, double(dims_.y()))));
      const int x1 = static_cast<int>(std::floor(std::clamp(hi.x(), -1.0, dims_.x() - 1.0)));
      const int y1 = static_cast<int>(std::floor(std::clamp(hi.y(), -1.0, dims_.y() - 1.0)));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          uint8_t& s = state_[linear(x, y, z)];
          if (s == kBlocked) continue;
          const Eigen::Vector3d centre = bounds_.min + cell_ * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
          if (squaredDistanceToTriangle(centre, a, b, c) <= r2) {
            s = kBlocked;
            ++blocked[layer];
          }
        }
      }
    }
  });
  blocked_ = 0;
  for (size_t n : blocked) blocked_ += n;
}

void FreeSpaceGrid::floodFromOutside() {
  std::vector<Eigen::Vector3i> stack;
  auto visit = [&](int x, int y, int z) {
    uint8_t& s = state_[linear(x, y, z)];
    if (s != kFree) return;
    s = kReachable;
    stack.emplace_back(x, y, z);
  };
  const Eigen::Vector3i& d = dims_;
  for (int z = 0; z < d.z(); ++z) {
    for (int y = 0; y < d.y(); ++y) {
      for (int x = 0; x < d.x(); ++x) {
        const bool side = x == 0 || y == 0 || x == d.x() - 1 || y == d.y() - 1 || z == d.z() - 1;
        if (side) visit(x, y, z);
      }
    }
  }
  while (!stack.empty()) {
    const Eigen::Vector3i c = stack.back();
    stack.pop_back();
    if (c.x() > 0) visit(c.x() - 1, c.y(), c.z());
    if (c.x() + 1 < d.x()) visit(c.x() + 1, c.y(), c.z());
    if (c.y() > 0) visit(c.x(), c.y() - 1, c.z());
    if (c.y() + 1 < d.y()) visit(c.x(), c.y() + 1, c.z());
    if (c.z() > 0) visit(c.x(), c.y(), c.z() - 1);
    if (c.z() + 1 < d.z()) visit(c.x(), c.y(), c.z() + 1);
  }
  reachable_ = static_cast<size_t>(std::count(state_.begin(), state_.end(), kReachable));
}

// Breadth-first from every reachable cell through the 26-neighbourhood.
void FreeSpaceGrid::measureClearance() {
  clearance_.assign(state_.size(), 255);
  std::vector<Eigen::Vector3i> frontier, next;
  for (int z = 0; z < dims_.z(); ++z) {
    for (int y = 0; y < dims_.y(); ++y) {
      for (int x = 0; x < dims_.x(); ++x) {
        if (state_[linear(x, y, z)] != kReachable) continue;
        clearance_[linear(x, y, z)] = 0;
        frontier.emplace_back(x, y, z);
      }
    }
  }
  for (int distance = 1; distance < 255 && !frontier.empty(); ++distance) {
    next.clear();
    for (const Eigen::Vector3i& c : frontier) {
      for (int dz = -1; dz <= 1; ++dz) {
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const Eigen::Vector3i n = c + Eigen::Vector3i(dx, dy, dz);
            if ((n.array() < 0).any() || (n.array() >= dims_.array()).any()) continue;
            uint8_t& d = clearance_[linear(n.x(), n.y(), n.z())];
            if (d <= distance) continue;
            d = static_cast<uint8_t>(distance);
            next.push_back(n);
          }
        }
      }
    }
    frontier.swap(next);
  }
}

}  // namespace surface_nbv
