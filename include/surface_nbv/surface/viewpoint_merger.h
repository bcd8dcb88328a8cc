// Merges viewpoint poses that are nearly the same (docs/method.md, "Viewpoint for
// an ISE"). In input order, a pose joins the first group whose seed (first
// pose) is closer than epsilon, or closer than parallel_distance with view
// directions whose dot product is at least parallel_cos; otherwise it seeds
// a new group. A group becomes one viewpoint at the mean position, looking
// along the mean view direction; when that mean pose is outside the bounds
// or not collision-free, the seed's pose stands. Seeds, not running means,
// decide membership, so a group cannot drift along a chain of poses, and the
// result depends only on the input order. The paper's test |n_i . n_j| ~ 1
// also takes opposite directions; those are not merged here, since the mean
// of two opposite orientations looks at neither. Const: thread-safe.
#pragma once

#include <vector>

#include "surface_nbv/common.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/surface/surface_config.h"

namespace surface_nbv {

class ViewpointMerger {
 public:
  // `config` must validate(); the constructor trusts it.
  explicit ViewpointMerger(const SurfaceConfig& config) : config_(config) {}

  // Whether pose b would join the group seeded by pose a.
  bool mergeable(const Viewpoint& a, const Viewpoint& b) const;

  // The merged viewpoints; their `sources` are the concatenated sources of
  // their poses, ascending. *group_of (if given) receives, per input pose,
  // the index of the viewpoint it went into.
  std::vector<Viewpoint> merge(const std::vector<Viewpoint>& poses, const CollisionMap& collision,
                               const AlignedBox& bounds, std::vector<int>* group_of = nullptr) const;

 private:
  SurfaceConfig config_;
};

}  // namespace surface_nbv
