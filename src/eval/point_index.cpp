#include "surface_nbv/eval/point_index.h"

#include <pcl/features/normal_3d.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>

namespace surface_nbv {

struct PointIndex::Impl {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud{new pcl::PointCloud<pcl::PointXYZ>};
  std::vector<int> original;                    // tree index -> index into the full set
  pcl::KdTreeFLANN<pcl::PointXYZ> tree{false};  // unsorted radius results: faster, still repeatable

  // Per-thread scratch for PCL's outputs.
  static pcl::Indices& scratchIndices() {
    thread_local pcl::Indices indices;
    return indices;
  }
  static std::vector<float>& scratchDistances() {
    thread_local std::vector<float> distances;
    return distances;
  }
};

PointIndex::PointIndex(const std::vector<Eigen::Vector3f>& points, const std::vector<uint8_t>* mask)
    : impl_(std::make_unique<Impl>()) {
  for (size_t i = 0; i < points.size(); ++i) {
    if (mask != nullptr && (*mask)[i] == 0) continue;
    impl_->cloud->push_back(pcl::PointXYZ(points[i].x(), points[i].y(), points[i].z()));
    impl_->original.push_back(static_cast<int>(i));
  }
  if (!impl_->cloud->empty()) impl_->tree.setInputCloud(impl_->cloud);
}

PointIndex::~PointIndex() = default;

size_t PointIndex::size() const { return impl_->original.size(); }

bool PointIndex::nearest(const Eigen::Vector3f& p, int* index, float* distance) const {
  if (impl_->original.empty()) return false;
  pcl::Indices& found = Impl::scratchIndices();
  std::vector<float>& sq = Impl::scratchDistances();
  found.resize(1);
  sq.resize(1);
  if (impl_->tree.nearestKSearch(pcl::PointXYZ(p.x(), p.y(), p.z()), 1, found, sq) < 1) return false;
  *index = impl_->original[found[0]];
  *distance = std::sqrt(sq[0]);
  return true;
}

void PointIndex::withinRadius(const Eigen::Vector3f& p, double radius, std::vector<int>* indices) const {
  indices->clear();
  if (impl_->original.empty()) return;
  pcl::Indices& found = Impl::scratchIndices();
  std::vector<float>& sq = Impl::scratchDistances();
  impl_->tree.radiusSearch(pcl::PointXYZ(p.x(), p.y(), p.z()), radius, found, sq);
  indices->reserve(found.size());
  for (const pcl::index_t i : found) indices->push_back(impl_->original[i]);
}

bool PointIndex::pcaNormal(const Eigen::Vector3f& p, double radius, Eigen::Vector3f* normal) const {
  if (impl_->original.empty()) return false;
  pcl::Indices& found = Impl::scratchIndices();
  std::vector<float>& sq = Impl::scratchDistances();
  if (impl_->tree.radiusSearch(pcl::PointXYZ(p.x(), p.y(), p.z()), radius, found, sq) < 3) return false;
  Eigen::Vector4f plane;
  float curvature = 0.0f;
  if (!pcl::computePointNormal(*impl_->cloud, found, plane, curvature) || !plane.head<3>().allFinite()) return false;
  *normal = plane.head<3>().normalized();
  return true;
}

}  // namespace surface_nbv
