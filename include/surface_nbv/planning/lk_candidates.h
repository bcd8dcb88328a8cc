// Candidate lists for KOptLocalSearch: for each node, the few nodes worth
// joining it to, best first. Two measures:
//   - nearest: cost itself, for symmetric matrices.
//   - assignment: for an asymmetric matrix in Jonker-Volgenant form, the
//     reduced cost c(i, j) - u(i) - v(j) >= 0 of the optimal assignment
//     (cycle cover) with duals u, v, the ATSP analogue of LKH's alpha-nearness:
//     arcs of good tours have small reduced costs even when their cost is not
//     among the smallest of their row or column. Ties go to the cheaper arc.
// Pure functions of their inputs, thread-safe.
#pragma once

#include <vector>

#include "surface_nbv/planning/cost_matrix.h"

namespace surface_nbv {

// Nearest `count` nodes of each node by cost, leaving out edges of cost >=
// `forbidden` and the fixed partner (fixed[a], -1 = none).
std::vector<std::vector<int>> nearestCandidates(const CostMatrix& costs, const std::vector<int>& fixed,
                                                double forbidden, int count);

// Reduced costs rc(i, j) of an optimal assignment of the n x n matrix `atsp`
// (the diagonal excluded; rc(i, i) is returned as +infinity), row-major.
// O(n^3) worst case, about 50 ms at n = 1000 on random matrices. If `bound`
// is given it receives the assignment cost, a lower bound on every tour.
std::vector<double> assignmentReducedCosts(const CostMatrix& atsp, double* bound = nullptr);

// Candidate lists of the 2n-node Jonker-Volgenant form of `atsp` (in node i,
// out node n + i): out node n + i gets the in nodes j with the `count` smallest
// rc(i, j), in node j the out nodes n + i with the smallest rc(i, j).
std::vector<std::vector<int>> assignmentCandidates(const CostMatrix& atsp, int count);

}  // namespace surface_nbv
