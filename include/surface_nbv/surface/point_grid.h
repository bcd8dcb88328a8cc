// Buckets of points in cubic cells for neighbour queries: the cells cover the
// bounding box given at construction, are at least `radius` wide (wider when
// the box would need more than kMaxCellsPerAxis per axis), so every point
// within `radius` of a query lies in the 27 cells around it. Points outside
// the box go to the nearest cell. Ids are the caller's (0 .. capacity - 1).
// Not thread-safe for inserts; queries are const.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "surface_nbv/common.h"

namespace surface_nbv {

class PointGrid {
 public:
  static constexpr int kMaxCellsPerAxis = 128;

  PointGrid(const AlignedBox& box, double radius, size_t capacity) : origin_(box.min), next_(capacity, -1) {
    const Eigen::Vector3d size = box.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(box.size());
    cell_ = std::max({radius, size.maxCoeff() / kMaxCellsPerAxis, 1e-9});
    cells_ = ((size / cell_).array().floor().cast<int>() + 1).min(kMaxCellsPerAxis);
    if (box.empty()) origin_.setZero();
    head_.assign(static_cast<size_t>(cells_.prod()), -1);
  }

  void insert(int id, const Eigen::Vector3d& p) {
    const size_t c = linear(cellOf(p));
    next_[id] = head_[c];
    head_[c] = id;
  }

  // Calls fn(id) for every point in the 27 cells around p: a superset of the
  // points within `radius` of p, in no particular order.
  template <typename Fn>
  void forEachNear(const Eigen::Vector3d& p, Fn&& fn) const {
    const Eigen::Vector3i c = cellOf(p);
    const Eigen::Vector3i lo = (c.array() - 1).max(0), hi = (c.array() + 1).min(cells_.array() - 1);
    for (int z = lo.z(); z <= hi.z(); ++z)
      for (int y = lo.y(); y <= hi.y(); ++y)
        for (int x = lo.x(); x <= hi.x(); ++x)
          for (int id = head_[linear(Eigen::Vector3i(x, y, z))]; id >= 0; id = next_[id]) fn(id);
  }

 private:
  Eigen::Vector3i cellOf(const Eigen::Vector3d& p) const {
    const Eigen::Array3d f = ((p - origin_) / cell_).array().floor().max(0.0);
    return f.min(cells_.cast<double>().array() - 1.0).cast<int>();
  }
  size_t linear(const Eigen::Vector3i& c) const {
    return static_cast<size_t>(c.x()) +
           static_cast<size_t>(cells_.x()) * (static_cast<size_t>(c.y()) + static_cast<size_t>(cells_.y()) * c.z());
  }

  Eigen::Vector3d origin_;
  double cell_ = 1.0;
  Eigen::Vector3i cells_;
  std::vector<int32_t> head_;
  std::vector<int32_t> next_;
};

}  // namespace surface_nbv
