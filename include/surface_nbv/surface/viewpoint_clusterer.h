// Clusters of viewpoints (docs/method.md, "Clusters") and their gains (eq. 3).
// q_i and q_j are neighbours when the straight segment between them is
// shorter than d_nu and collision-free with the configured radius (that
// segment stands for the roadmap path; when it is blocked they are not
// neighbours here). A viewpoint with no neighbour widens its own radius by
// d_nu_step up to d_nu_max and links to every viewpoint within the first
// radius that finds one. Clusters are the connected components (q_i joins u
// if some q_j in u is its neighbour), numbered by their smallest viewpoint,
// g(u) = |union of C_q over u| / |C|. Runs on `threads` threads, same result
// for any count.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/surface/surface_config.h"

namespace surface_nbv {

class ViewpointClusterer {
 public:
  // `config` must validate(); the constructor trusts it.
  explicit ViewpointClusterer(const SurfaceConfig& config) : config_(config) {}

  // Sets viewpoints[i].cluster and returns the clusters with their gains,
  // |C| = num_ises (0 gives zero gains). *links receives the edges used.
  std::vector<Cluster> cluster(const CollisionMap& collision, size_t num_ises, std::vector<Viewpoint>* viewpoints,
                               std::vector<std::pair<int, int>>* links = nullptr) const;

  // Whether a ball of the collision radius can move from a to b in a
  // straight line: samples spaced by the clearance the distance map
  // certifies, at most half a collision cell apart, and b itself.
  bool segmentFree(const CollisionMap& collision, const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;

 private:
  SurfaceConfig config_;
};

}  // namespace surface_nbv
