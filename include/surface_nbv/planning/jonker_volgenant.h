// Jonker-Volgenant 2-node transform of an asymmetric TSP on n nodes into a
// symmetric one on 2n nodes: node i becomes an "in" node i and an "out" node
// n + i joined by a pair edge; the arc i -> j becomes the edge {n + i, j}.
//   d(i, n + i)  = 0                      (pair edge)
//   d(n + i, j)  = c(i, j) + offset       (i != j)
//   every other  = forbidden              (in-in, out-out)
// With offset > n * (max c - min c) every optimal symmetric tour uses all n
// pair edges (it has exactly n non-pair edges; one more would cost more than
// any saving), and forbidden > 2n * (max c + offset) keeps forbidden edges out
// of every optimal tour: an exact symmetric solver then solves the ATSP, with
// symmetric cost = ATSP cost + n * offset. A heuristic that never removes the
// pair edges may use offset 0.
#pragma once

#include <vector>

#include "surface_nbv/planning/cost_matrix.h"

namespace surface_nbv {

struct JvTransform {
  CostMatrix symmetric;  // 2n x 2n
  double offset = 0.0;
  double forbidden = 0.0;
  int atsp_nodes = 0;
};

// offset < 0 chooses the safe offset n * (max c - min c) + 1.
JvTransform jonkerVolgenant(const CostMatrix& atsp, double offset = -1.0);

// An ATSP tour i0 i1 ... as the symmetric tour i0 (n+i0) i1 (n+i1) ...
std::vector<int> atspToSymmetricTour(const std::vector<int>& atsp_tour, int atsp_nodes);

// The inverse: walks the symmetric tour in the direction that goes from each
// in node to its out node. Returns false (and leaves *atsp_tour empty) if the
// tour is not a permutation of 2n nodes containing every pair edge.
bool symmetricToAtspTour(const std::vector<int>& symmetric_tour, int atsp_nodes, std::vector<int>* atsp_tour);

}  // namespace surface_nbv
