#include "surface_nbv/eval/m3c2_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {
namespace {

constexpr size_t kChunk = 1024;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

}  // namespace

M3c2Distance::M3c2Distance(const EvalConfig& config)
    : config_(config),
      radius_(config.projectionRadius()),
      depth_(config.maxDepth()),
      search_radius_(std::hypot(radius_, depth_)),
      cos_agreement_(std::cos(config.normal_agreement_deg * M_PI / 180.0) - 1e-9) {}

double M3c2Distance::meanProjection(const Eigen::Vector3f& p, const Eigen::Vector3f& n, const SurfaceCloud& cloud,
                                    const PointIndex& index) const {
  thread_local std::vector<int> found;
  index.withinRadius(p, search_radius_, &found);
  const Eigen::Vector3d pd = p.cast<double>(), nd = n.cast<double>();
  const double r2 = radius_ * radius_;
  double sum[2] = {0.0, 0.0};  // facing n, facing -n
  int count[2] = {0, 0};
  for (const int j : found) {
    const float agreement = cloud.normals[j].dot(n);
    if (std::abs(agreement) < cos_agreement_) continue;
    const Eigen::Vector3d v = cloud.points[j].cast<double>() - pd;
    const double along = v.dot(nd);
    if (std::abs(along) > depth_ || v.squaredNorm() - along * along > r2) continue;
    const int side = agreement > 0.0f ? 0 : 1;
    sum[side] += along;
    ++count[side];
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double facing = count[0] >= config_.min_neighbours ? sum[0] / count[0] : nan;
  const double opposing = count[1] >= config_.min_neighbours ? sum[1] / count[1] : nan;
  if (std::isnan(opposing)) return facing;
  if (std::isnan(facing)) return opposing;
  return std::abs(opposing) < std::abs(facing) ? opposing : facing;
}

float M3c2Distance::at(const Eigen::Vector3f& p, const Eigen::Vector3f& n, const SurfaceCloud& reference,
                       const PointIndex& reference_index, const SurfaceCloud& compared,
                       const PointIndex& compared_index) const {
  Eigen::Vector3f axis = n;
  if (config_.normal_radius > 0.0 && reference_index.pcaNormal(p, config_.normal_radius, &axis)) {
    if (axis.dot(n) < 0.0f) axis = -axis;
  }
  const double base = meanProjection(p, axis, reference, reference_index);
  const double moved = meanProjection(p, axis, compared, compared_index);
  return std::isfinite(base) && std::isfinite(moved) ? static_cast<float>(moved - base) : kNaN;
}

std::vector<float> M3c2Distance::compute(const SurfaceCloud& reference, const PointIndex& reference_index,
                                         const SurfaceCloud& compared, const PointIndex& compared_index,
                                         const std::vector<uint8_t>& core) const {
  const size_t n = reference.size();
  std::vector<float> distances(n, kNaN);
  parallelFor((n + kChunk - 1) / kChunk, config_.threads, [&](size_t chunk) {
    const size_t end = std::min(n, (chunk + 1) * kChunk);
    for (size_t i = chunk * kChunk; i < end; ++i) {
      if (core[i] == 0) continue;
      distances[i] =
          at(reference.points[i], reference.normals[i], reference, reference_index, compared, compared_index);
    }
  });
  return distances;
}

}  // namespace surface_nbv
