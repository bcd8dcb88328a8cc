// Exact closed-tour ATSP by Held-Karp dynamic programming, O(2^n n^2) time and
// O(2^n n) memory, for n <= kHeldKarpMaxNodes. The tour starts at node 0.
// Status: kExactSolution, kEmptyInput, or kInvalidInput (bad costs or n too large).
#pragma once

#include "surface_nbv/planning/cost_matrix.h"
#include "surface_nbv/planning/tour_result.h"

namespace surface_nbv {

constexpr int kHeldKarpMaxNodes = 13;

TourResult heldKarp(const CostMatrix& costs);

}  // namespace surface_nbv
