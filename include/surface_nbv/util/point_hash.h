// Points hashed into cubes of `cell` metres, for "is any point within r"
// and "which point is nearest within r" queries with r <= cell (the explorer
// matches tour and frontier viewpoints with it).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace surface_nbv {

class PointHash {
 public:
  explicit PointHash(double cell) : cell_(cell) {}
  void add(const Eigen::Vector3d& p, int id) { cells_[key(cellOf(p))].push_back({p, id}); }
  // Calls f(id) for every point within r of p, stops when f returns true; true if one did.
  template <typename F>
  bool any(const Eigen::Vector3d& p, double r, F f) const {
    return visit(p, [&](const Eigen::Vector3d& q, int id) { return (q - p).norm() <= r && f(id); });
  }
  // The id of the point nearest p within r, of equally near ones the largest
  // id; -1 when none is that near.
  int nearest(const Eigen::Vector3d& p, double r) const {
    int best = -1;
    double best_distance = r;
    visit(p, [&](const Eigen::Vector3d& q, int id) {
      const double distance = (q - p).norm();
      if (distance < best_distance || (distance == best_distance && id > best)) best = id, best_distance = distance;
      return false;
    });
    return best;
  }
  void clear() { cells_.clear(); }

 private:
  // Calls f(point, id) for the points of p's cell and its 26 neighbours
  // until f returns true; true if it did.
  template <typename F>
  bool visit(const Eigen::Vector3d& p, F f) const {
    const Eigen::Vector3i c = cellOf(p);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const auto& e : it->second)
            if (f(e.first, e.second)) return true;
        }
    return false;
  }
  Eigen::Vector3i cellOf(const Eigen::Vector3d& p) const { return (p / cell_).array().floor().cast<int>(); }
  static int64_t key(const Eigen::Vector3i& c) {
    return (static_cast<int64_t>(c.x()) * 73856093) ^ (static_cast<int64_t>(c.y()) * 19349663) ^
           (static_cast<int64_t>(c.z()) * 83492791);
  }
  double cell_;
  std::unordered_map<int64_t, std::vector<std::pair<Eigen::Vector3d, int>>> cells_;
};

}  // namespace surface_nbv
