#include "surface_nbv/surface/surface_config.h"

#include <cmath>
#include <string>

namespace surface_nbv {
namespace {

bool finite(double v) { return std::isfinite(v); }

}  // namespace

Status SurfaceConfig::validate() const {
  if (Status s = camera.validate(); !s) return s;
  if (!finite(delta_pose) || delta_pose <= 0.0) return Status::Error("delta_pose expected > 0");
  if (delta_pose > camera.max_range) return Status::Error("delta_pose expected <= camera/max_range");
  for (double a : fallback_rotations_deg) {
    if (!finite(a) || a <= 0.0 || a > 180.0) return Status::Error("fallback_rotations_deg expected values in (0, 180]");
  }
  for (double f : fallback_distance_fractions) {
    if (!finite(f) || f <= 0.0 || f >= 1.0) return Status::Error("fallback_distance_fractions expected values in (0, 1)");
  }
  if (!finite(approach_range_fraction) || approach_range_fraction < 0.0 || approach_range_fraction > 1.0) {
    return Status::Error("approach_range_fraction expected in [0, 1]");
  }
  if (!finite(fov_margin_deg) || fov_margin_deg < 0.0 || fov_margin_deg >= 0.5 * camera.vfov_deg) {
    return Status::Error("fov_margin_deg expected in [0, camera/vfov_deg / 2)");
  }
  if (!finite(collision_radius) || collision_radius <= 0.0) return Status::Error("collision_radius expected > 0");
  if (!finite(epsilon) || epsilon <= 0.0) return Status::Error("epsilon expected > 0");
  if (!finite(parallel_distance) || parallel_distance < 0.0) return Status::Error("parallel_distance expected >= 0");
  if (!finite(parallel_cos) || parallel_cos < -1.0 || parallel_cos > 1.0) {
    return Status::Error("parallel_cos expected in [-1, 1]");
  }
  if (!finite(d_nu) || d_nu <= 0.0) return Status::Error("d_nu expected > 0");
  if (!finite(d_nu_max) || d_nu_max < d_nu) return Status::Error("d_nu_max expected >= d_nu");
  if (!finite(d_nu_step) || d_nu_step <= 0.0) return Status::Error("d_nu_step expected > 0");
  if (threads < 1 || threads > 64) return Status::Error("threads expected in [1, 64]");
  return Status::Ok();
}

}  // namespace surface_nbv
