// Keeps the ground-truth samples some collision-free sensor position can see
// (docs/method.md, "Evaluation protocol"). From each sample, lines of sight are
// cast with Embree along up to `visibility_rays` directions per side of its
// triangle, within max_incidence_deg of the normal; the sample is visible when
// one reaches a reachable FreeSpaceGrid cell at a distance in [min_range,
// max_range] before it hits a triangle. Const and thread safe.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "surface_nbv/eval/eval_config.h"
#include "surface_nbv/eval/free_space_grid.h"
#include "surface_nbv/eval/surface_sampler.h"
#include "surface_nbv/sim/raycast_scene.h"

namespace surface_nbv {

class VisibilityPruner {
 public:
  // `scene` holds the ground-truth mesh; both references must outlive the pruner.
  VisibilityPruner(const RaycastScene& scene, const FreeSpaceGrid& free_space, const EvalConfig& config);

  // Sets visible[i] to 1 for the visible samples and turns their normals to
  // the side they are seen from (hidden samples keep theirs). Returns how many are visible.
  size_t prune(SurfaceCloud* cloud, std::vector<uint8_t>* visible) const;

  // The side of the surface (+1 along n, -1 against it) sample `index` at p
  // is seen from, or 0 when no line of sight reaches free space.
  int seenSide(const Eigen::Vector3d& p, const Eigen::Vector3d& n, uint64_t index) const;

 private:
  bool lineOfSight(const Eigen::Vector3d& p, const Eigen::Vector3d& direction) const;

  const RaycastScene& scene_;
  const FreeSpaceGrid& free_space_;
  EvalConfig config_;
  std::vector<Eigen::Vector3d> cone_;  // unit directions around +z, the first one +z
};

}  // namespace surface_nbv
