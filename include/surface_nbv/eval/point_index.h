// A kd-tree (PCL's KdTreeFLANN, exact search) over a point set or the masked
// part of it, answering with indices into the full set. PCL stays behind
// this header. Built once; the const queries are thread safe.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

namespace surface_nbv {

class PointIndex {
 public:
  // Indexes points[i] for every i with (*mask)[i] != 0, or all without a mask.
  explicit PointIndex(const std::vector<Eigen::Vector3f>& points, const std::vector<uint8_t>* mask = nullptr);
  ~PointIndex();
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  size_t size() const;
  // The nearest indexed point; false when the index is empty.
  bool nearest(const Eigen::Vector3f& p, int* index, float* distance) const;
  // The indexed points within `radius` of p (cleared first), in the tree's order.
  void withinRadius(const Eigen::Vector3f& p, double radius, std::vector<int>* indices) const;
  // Unit normal of the plane fitted (PCA) to the indexed points within
  // `radius` of p, sign arbitrary; false with fewer than 3 points.
  bool pcaNormal(const Eigen::Vector3f& p, double radius, Eigen::Vector3f* normal) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace surface_nbv
