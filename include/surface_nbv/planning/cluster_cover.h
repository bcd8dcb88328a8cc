// Fewer viewpoints per cluster: a greedy set cover of each cluster's ISEs
// (the union of its viewpoints' C_q) by its viewpoints. The tour flies every
// viewpoint of a cluster (tau_lm), and viewpoints within d_nu of each other
// mostly see the same ISEs, so a cluster's ISEs are usually seen from a few
// of them. ROS-free.
#pragma once

#include <cstddef>
#include <vector>

#include "surface_nbv/surface/frontier.h"

namespace surface_nbv {

struct ClusterCoverStats {
  size_t kept = 0, dropped = 0;  // viewpoints of clusters
};

// Within each cluster of `frontier`, keeps the viewpoints chosen by a greedy
// cover and takes the others out of the cluster (their `cluster` becomes -1).
// Preferred viewpoints (preferred[i] > 0, e.g. the current target 2 and
// the rest of the tour 1, so that the tour does not change its mind every
// update) are taken first, higher priorities first, each if it adds an ISE
// not yet seen; then, repeatedly, the viewpoint that adds the most such ISEs
// (ties: the lowest index), while that is at least min_new (a cluster keeps
// at least one viewpoint). A cluster keeps its gain and visible_ises.
// `preferred` may be shorter than the viewpoints (the rest: 0).
Frontier coverClusters(const Frontier& frontier, const std::vector<char>& preferred, size_t min_new,
                       ClusterCoverStats* stats = nullptr);

}  // namespace surface_nbv
