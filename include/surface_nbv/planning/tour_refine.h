// 2-opt on the explorer's viewpoint tour between full recomputations
// (ExplorerConfig::refine_tour). The local update inserts new viewpoints where
// they cost least and keeps the order of the rest, so over hundreds of
// updates the tour can cross itself; this removes the crossings without
// re-solving the tour from scratch, which changes its head from update to
// update (docs/planner_experiments.md, full_on_leg_end). ROS-free.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace surface_nbv {

// The open path start -> tour[0] -> ... -> tour[n-1] in straight-line length
// (positions: the first three coordinates).
double openPathLength(const Eigen::Vector3d& start, const std::vector<Eigen::Vector4d>& tour);

// Shortens that open path by 2-opt moves (reversing tour[i..j]; the path's
// end is free, so a reversal that reaches the end replaces one edge only)
// until none gains more than 1e-9 m or max_passes passes over all (i, j)
// were made. tour[0 .. fixed-1] keep their places (the current target).
// Deterministic: first improving move in (i, j) order. Returns the number
// of moves made; the path never gets longer.
size_t twoOptOpenPath(const Eigen::Vector3d& start, size_t fixed, int max_passes, std::vector<Eigen::Vector4d>* tour);

}  // namespace surface_nbv
