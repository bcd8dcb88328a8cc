#include "surface_nbv/eval/visibility_pruner.h"

#include <algorithm>
#include <cmath>

#include "surface_nbv/eval/counter_random.h"
#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {
namespace {

constexpr size_t kChunk = 1024;
constexpr uint64_t kStreamTwist = 0x7a15;
// Lines of sight start this far off the surface, on the side they test, so a
// sample on an edge cannot see through the face meeting it there.
constexpr double kLift = 1e-3;  // m

// Two unit vectors completing n to a right-handed orthonormal frame.
void frameAround(const Eigen::Vector3d& n, Eigen::Vector3d* t1, Eigen::Vector3d* t2) {
  const Eigen::Vector3d helper = std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  *t1 = n.cross(helper).normalized();
  *t2 = n.cross(*t1);
}

// [t0, t1] of origin + t * direction inside `box`, clipped to the given
// interval; false when empty.
bool clipToBox(const AlignedBox& box, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double* t0,
               double* t1) {
  for (int a = 0; a < 3; ++a) {
    if (direction[a] == 0.0) {
      if (origin[a] < box.min[a] || origin[a] > box.max[a]) return false;
      continue;
    }
    double lo = (box.min[a] - origin[a]) / direction[a];
    double hi = (box.max[a] - origin[a]) / direction[a];
    if (lo > hi) std::swap(lo, hi);
    *t0 = std::max(*t0, lo);
    *t1 = std::min(*t1, hi);
  }
  return *t0 <= *t1;
}

}  // namespace

VisibilityPruner::VisibilityPruner(const RaycastScene& scene, const FreeSpaceGrid& free_space, const EvalConfig& config)
    : scene_(scene), free_space_(free_space), config_(config) {
  // Area-uniform spiral over the cap of half-angle max_incidence around +z.
  const int k = config.visibility_rays;
  const double cos_max = std::cos(config.max_incidence_deg * M_PI / 180.0);
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int j = 0; j < k; ++j) {
    const double z = k == 1 ? 1.0 : 1.0 - (1.0 - cos_max) * j / (k - 1);
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    cone_.emplace_back(s * std::cos(golden * j), s * std::sin(golden * j), z);
  }
}

bool VisibilityPruner::lineOfSight(const Eigen::Vector3d& p, const Eigen::Vector3d& direction) const {
  double t_hit = 0.0;
  double t0 = config_.min_range;
  double t1 = scene_.intersect(p, direction, 0.0, config_.max_range, &t_hit) ? t_hit : config_.max_range;
  if (t0 > t1 || !clipToBox(free_space_.bounds(), p, direction, &t0, &t1)) return false;
  // March in half cells, leaping over stretches known to be far from any reachable cell.
  const double step = 0.5 * config_.free_space_cell;
  for (double t = t0;;) {
    const double at = std::min(t, t1);
    const int cells = free_space_.cellsToReachable(p + at * direction);
    if (cells == 0) return true;
    if (at >= t1) return false;
    t = at + std::max(step, (cells - 1) * free_space_.cellSize());
  }
}

int VisibilityPruner::seenSide(const Eigen::Vector3d& p, const Eigen::Vector3d& n, uint64_t index) const {
  Eigen::Vector3d t1, t2;
  frameAround(n, &t1, &t2);
  // A per-sample twist about n, so neighbouring samples try different directions.
  const double twist = 2.0 * M_PI * counterUniform(config_.seed, kStreamTwist, index);
  const double c = std::cos(twist), s = std::sin(twist);
  for (const Eigen::Vector3d& d : cone_) {
    const Eigen::Vector3d tangent = (c * d.x() - s * d.y()) * t1 + (s * d.x() + c * d.y()) * t2;
    if (lineOfSight(p + kLift * n, tangent + d.z() * n)) return 1;
    if (lineOfSight(p - kLift * n, tangent - d.z() * n)) return -1;
  }
  return 0;
}

size_t VisibilityPruner::prune(SurfaceCloud* cloud, std::vector<uint8_t>* visible) const {
  const size_t n = cloud->size();
  visible->assign(n, 0);
  parallelFor((n + kChunk - 1) / kChunk, config_.threads, [&](size_t chunk) {
    const size_t end = std::min(n, (chunk + 1) * kChunk);
    for (size_t i = chunk * kChunk; i < end; ++i) {
      const int side = seenSide(cloud->points[i].cast<double>(), cloud->normals[i].cast<double>(), i);
      (*visible)[i] = side != 0 ? 1 : 0;
      if (side < 0) cloud->normals[i] = -cloud->normals[i];
    }
  });
  return static_cast<size_t>(std::count(visible->begin(), visible->end(), 1));
}

}  // namespace surface_nbv
