// Exact nearest neighbours of points in 3D over a uniform grid of cells, as
// an OMPL NearestNeighbors structure for the roadmap (PathPlanner).
//
// OMPL's default (GNAT) rebuilds its whole tree whenever a removed element
// was one of its pivots, and a lazy roadmap removes vertices all the time (a
// vertex found inside an obstacle is removed): on the power plant the
// rebuilds and removals took about 15 % of a mission's run time. Here an
// element is added to and removed from one cell's list; a k-nearest query
// scans rings of cells outwards until no unscanned cell can hold a closer
// point. Distances are computed as RealVectorStateSpace::distance computes
// them (the same bits), results are sorted by distance, ties by insertion
// order. The cell size follows the element count (about kPerCell elements per
// cell over the bounds; the grid is rebuilt when the count doubles or halves).
// Thread safety: none (as OMPL's NoThreadSafety structures).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <ompl/datastructures/NearestNeighbors.h>
#include <ompl/util/Exception.h>

namespace surface_nbv {

template <typename T>
class GridNeighbors : public ompl::NearestNeighbors<T> {
 public:
  using Position = std::function<Eigen::Vector3d(const T&)>;
  static constexpr double kPerCell = 4.0;

  // position: where an element is (fixed while it is stored); [lo, hi]: the
  // box the elements lie in (elements outside are clamped to its border cells).
  GridNeighbors(Position position, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi)
      : position_(std::move(position)), lo_(lo), extent_((hi - lo).cwiseMax(1e-9)) {
    rebuild(0);
  }

  bool reportsSortedResults() const override { return true; }

  void clear() override {
    entries_.clear();
    slot_.clear();
    free_.clear();
    size_ = 0;
    rebuild(0);
  }

  void add(const T& data) override {
    uint32_t id;
    if (!free_.empty()) {
      id = free_.back();
      free_.pop_back();
    } else {
      id = static_cast<uint32_t>(entries_.size());
      entries_.emplace_back();
    }
    Entry& e = entries_[id];
    e.data = data;
    e.p = position_(data);
    e.order = next_order_++;
    e.alive = true;
    slot_[data] = id;
    cell(cellOf(e.p)).push_back(id);
    if (++size_ > 2 * built_for_ && size_ > 64) rebuild(size_);
  }

  bool remove(const T& data) override {
    const auto it = slot_.find(data);
    if (it == slot_.end()) return false;
    const uint32_t id = it->second;
    slot_.erase(it);
    std::vector<uint32_t>& ids = cell(cellOf(entries_[id].p));
    ids.erase(std::find(ids.begin(), ids.end(), id));
    entries_[id].alive = false;
    free_.push_back(id);
    if (--size_ < built_for_ / 4 && built_for_ > 64) rebuild(size_);
    return true;
  }

  T nearest(const T& data) const override {
    std::vector<T> one;
    nearestK(data, 1, one);
    if (one.empty()) throw ompl::Exception("No elements found in nearest neighbors data structure");
    return one.front();
  }

  void nearestK(const T& data, std::size_t k, std::vector<T>& nbh) const override {
    nbh.clear();
    if (k == 0 || size_ == 0) return;
    const Eigen::Vector3d q = position_(data);
    const Eigen::Vector3i c = cellOf(q);
    // Nearest first: (distance, insertion order) of at most k kept.
    std::vector<Found> best;
    const auto worse = [](const Found& a, const Found& b) { return a.d < b.d || (a.d == b.d && a.order < b.order); };
    const int max_ring = dims_.maxCoeff();
    for (int r = 0; r <= max_ring; ++r) {
      forRing(c, r, [&](const std::vector<uint32_t>& cell) {
        for (uint32_t id : cell) {
          const Entry& e = entries_[id];
          const Found f{distance(q, e.p), e.order, id};
          if (best.size() < k) {
            best.push_back(f);
            std::push_heap(best.begin(), best.end(), worse);
          } else if (worse(f, best.front())) {
            std::pop_heap(best.begin(), best.end(), worse);
            best.back() = f;
            std::push_heap(best.begin(), best.end(), worse);
          }
        }
      });
      // Every cell of ring r + 1 and beyond is at least r cells away from q's cell.
      if (best.size() == k && best.front().d <= r * cell_) break;
    }
    std::sort_heap(best.begin(), best.end(), worse);
    for (const Found& f : best) nbh.push_back(entries_[f.id].data);
  }

  void nearestR(const T& data, double radius, std::vector<T>& nbh) const override {
    nbh.clear();
    if (size_ == 0 || !(radius >= 0.0)) return;
    const Eigen::Vector3d q = position_(data);
    const Eigen::Vector3i c = cellOf(q);
    std::vector<Found> found;
    const int rings = std::min(dims_.maxCoeff(), static_cast<int>(std::ceil(radius / cell_)) + 1);
    for (int r = 0; r <= rings; ++r) {
      forRing(c, r, [&](const std::vector<uint32_t>& cell) {
        for (uint32_t id : cell) {
          const double d = distance(q, entries_[id].p);
          if (d <= radius) found.push_back({d, entries_[id].order, id});
        }
      });
    }
    std::sort(found.begin(), found.end(),
              [](const Found& a, const Found& b) { return a.d < b.d || (a.d == b.d && a.order < b.order); });
    for (const Found& f : found) nbh.push_back(entries_[f.id].data);
  }

  std::size_t size() const override { return size_; }

  void list(std::vector<T>& data) const override {
    data.clear();
    for (const Entry& e : entries_)
      if (e.alive) data.push_back(e.data);
  }

  double cellSize() const { return cell_; }

 private:
  struct Entry {
    T data{};
    Eigen::Vector3d p;
    uint64_t order = 0;
    bool alive = false;
  };
  struct Found {
    double d;
    uint64_t order;
    uint32_t id;
  };

  // As ompl::base::RealVectorStateSpace::distance: the same operations in the same order.
  static double distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double diff = a[i] - b[i];
      sum += diff * diff;
    }
    return std::sqrt(sum);
  }

  Eigen::Vector3i cellOf(const Eigen::Vector3d& p) const {
    Eigen::Vector3i c;
    for (int i = 0; i < 3; ++i) {
      const double x = std::floor((p[i] - lo_[i]) / cell_);
      c[i] = std::isfinite(x) ? static_cast<int>(std::clamp(x, 0.0, static_cast<double>(dims_[i] - 1))) : 0;
    }
    return c;
  }
  std::vector<uint32_t>& cell(const Eigen::Vector3i& c) { return grid_[index(c)]; }
  size_t index(const Eigen::Vector3i& c) const {
    return static_cast<size_t>(c.x()) + static_cast<size_t>(dims_.x()) * (c.y() + static_cast<size_t>(dims_.y()) * c.z());
  }

  // Calls f(cell) for every cell of the grid at Chebyshev distance r from c.
  template <typename F>
  void forRing(const Eigen::Vector3i& c, int r, F&& f) const {
    const Eigen::Vector3i lo = (c.array() - r).max(0), hi = (c.array() + r).min(dims_.array() - 1);
    const auto visit = [&](int x, int y, int z) {
      const std::vector<uint32_t>& ids = grid_[index(Eigen::Vector3i(x, y, z))];
      if (!ids.empty()) f(ids);
    };
    for (int z = lo.z(); z <= hi.z(); ++z)
      for (int y = lo.y(); y <= hi.y(); ++y) {
        if (std::abs(z - c.z()) == r || std::abs(y - c.y()) == r) {
          for (int x = lo.x(); x <= hi.x(); ++x) visit(x, y, z);  // a face of the ring: the whole row
        } else {
          if (c.x() - r >= 0) visit(c.x() - r, y, z);  // inside: the row's two ends
          if (r > 0 && c.x() + r < dims_.x()) visit(c.x() + r, y, z);
        }
      }
  }

  // A grid with about kPerCell of n elements per cell, holding every element.
  void rebuild(size_t n) {
    built_for_ = std::max<size_t>(n, 64);
    const double volume = extent_.prod();
    cell_ = std::cbrt(kPerCell * volume / static_cast<double>(built_for_));
    for (int i = 0; i < 3; ++i) {
      dims_[i] = std::max(1, std::min(1 << 10, static_cast<int>(std::ceil(extent_[i] / cell_))));
    }
    grid_.assign(static_cast<size_t>(dims_.prod()), {});
    for (uint32_t id = 0; id < entries_.size(); ++id)
      if (entries_[id].alive) grid_[index(cellOf(entries_[id].p))].push_back(id);
  }

  Position position_;
  Eigen::Vector3d lo_, extent_;
  double cell_ = 1.0;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Ones();
  std::vector<std::vector<uint32_t>> grid_;
  std::vector<Entry> entries_;
  std::unordered_map<T, uint32_t> slot_;
  std::vector<uint32_t> free_;
  size_t size_ = 0, built_for_ = 64;
  uint64_t next_order_ = 0;
};

}  // namespace surface_nbv
