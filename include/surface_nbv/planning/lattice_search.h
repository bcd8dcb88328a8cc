// A* over a regular lattice of positions, the path planner's fallback when
// its roadmap finds no path in its budget (narrow passages and tight spots,
// which random sampling rarely hits, are where it stalled for minutes).
//
// Nodes are start + step * (i, j, k) for integer i, j, k, 26-connected; an
// edge a -> b exists when motion_free(a, b) (which must also check b). The
// goal, usually off the lattice, is reached from any expanded node within
// 2 steps by a free straight motion. Costs are Euclidean lengths with the
// Euclidean distance to the goal as heuristic, so the path is the shortest
// on the lattice. Deterministic: ties break by insertion order.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace surface_nbv {

struct LatticeSearchResult {
  bool found = false;
  std::vector<Eigen::Vector3d> path;  // start ... goal when found
  size_t expanded = 0;                // nodes taken off the open list
  bool stopped = false;               // max_nodes or should_stop ended the search
};

LatticeSearchResult latticeSearch(const Eigen::Vector3d& start, const Eigen::Vector3d& goal, double step,
                                  size_t max_nodes,
                                  const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&)>& motion_free,
                                  const std::function<bool()>& should_stop);

}  // namespace surface_nbv
