// The tour over clusters as an open path from a fixed start (the UAV's current
// configuration) whose end is free. Reduction to a closed ATSP: every arc into
// the start costs 0. It is the usual dummy-node reduction (a dummy with 0-cost
// arcs from every node and a single 0-cost arc to the start) with the dummy
// merged into the start: a closed tour start -> ... -> last -> start then
// costs exactly the open path start -> ... -> last, so optimal tours and
// optimal paths correspond. Nothing else in the matrix changes, so a
// per-node constant added to the arcs into each node (utilityLogCost) still
// leaves the optimum unchanged.
#pragma once

#include "surface_nbv/planning/lin_kernighan_solver.h"

namespace surface_nbv {

// tour[0] == start; cost = sum of the n - 1 arcs of the path. Status
// kInvalidStart when start is not in [0, n); n = 1 gives the path {start}.
TourResult solveOpenPath(const CostMatrix& costs, int start,
                         const LinKernighanSolver::Config& config = LinKernighanSolver::Config());

}  // namespace surface_nbv
