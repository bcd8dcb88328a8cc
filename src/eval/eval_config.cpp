#include "surface_nbv/eval/eval_config.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {
namespace {

bool positive(double v) { return std::isfinite(v) && v > 0.0; }
bool nonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

double EvalConfig::eMax() const { return voxel_size * std::sqrt(3.0) / 2.0; }
double EvalConfig::spacing() const { return point_spacing > 0.0 ? point_spacing : voxel_size / 3.0; }
double EvalConfig::projectionRadius() const {
  return projection_radius > 0.0 ? projection_radius : std::max(voxel_size / 2.0, 1.5 * spacing());
}
double EvalConfig::maxDepth() const { return max_depth > 0.0 ? max_depth : eMax(); }

AlignedBox EvalConfig::sensorBounds(const AlignedBox& ground_truth_bounds) const {
  if (!bounds.empty()) return bounds;
  AlignedBox b(ground_truth_bounds.min - Eigen::Vector3d::Constant(bounds_margin),
               ground_truth_bounds.max + Eigen::Vector3d::Constant(bounds_margin));
  b.min.z() = ground_truth_bounds.min.z();
  return b;
}

Status EvalConfig::validate() const {
  if (!positive(voxel_size)) return Status::Error("voxel_size expected > 0");
  if (!nonNegative(point_spacing)) return Status::Error("point_spacing expected >= 0 (0 = voxel_size / 3)");
  if (max_points == 0) return Status::Error("max_points expected > 0");
  if (threads < 1 || threads > 64) return Status::Error("threads expected in [1, 64]");
  if (!bounds.empty() &&
      (!bounds.min.allFinite() || !bounds.max.allFinite() || (bounds.max.array() <= bounds.min.array()).any())) {
    return Status::Error("bounds expected finite with min < max on every axis (or empty for automatic bounds)");
  }
  if (!nonNegative(bounds_margin)) return Status::Error("bounds_margin expected >= 0");
  if (!nonNegative(min_range)) return Status::Error("min_range expected >= 0");
  if (!positive(max_range) || max_range <= min_range) return Status::Error("max_range expected > min_range");
  if (!nonNegative(collision_radius)) return Status::Error("collision_radius expected >= 0");
  if (!positive(free_space_cell)) return Status::Error("free_space_cell expected > 0");
  if (!(max_incidence_deg > 0.0 && max_incidence_deg < 90.0))
    return Status::Error("max_incidence_deg expected in (0, 90)");
  if (visibility_rays < 1 || visibility_rays > 4096) return Status::Error("visibility_rays expected in [1, 4096]");
  if (!nonNegative(projection_radius))
    return Status::Error("projection_radius expected >= 0 (0 = max(voxel_size / 2, 1.5 point spacings))");
  if (!nonNegative(max_depth)) return Status::Error("max_depth expected >= 0 (0 = e_max)");
  if (!nonNegative(normal_radius)) return Status::Error("normal_radius expected >= 0 (0 = triangle normals)");
  if (!(normal_agreement_deg > 0.0 && normal_agreement_deg <= 90.0)) {
    return Status::Error("normal_agreement_deg expected in (0, 90]");
  }
  if (min_neighbours < 1) return Status::Error("min_neighbours expected >= 1");
  return Status::Ok();
}

}  // namespace surface_nbv
