// Closed-tour TSP solver, symmetric or asymmetric: Held-Karp when n is small
// enough to prove the optimum, otherwise iterated Lin-Kernighan (LKH-style) on
// the Jonker-Volgenant symmetric form of an asymmetric matrix (pair edges
// fixed) or directly on a symmetric one. Candidates of an asymmetric matrix
// are ranked by the reduced costs of its optimal assignment (lk_candidates.h),
// of a symmetric one by cost. Each restart builds a nearest-neighbour tour from
// a random node, improves it with KOptLocalSearch (sequential 3-, 5- and 7-opt
// moves, Or-opt, don't-look bits), then runs max_trials kicks (double bridge +
// local search, accepted when not worse). With time_limit_s = 0 a run depends
// only on the seed and repeats exactly. solve() is const and thread-safe.
#pragma once

#include <cstdint>
#include <string>

#include "surface_nbv/planning/cost_matrix.h"
#include "surface_nbv/planning/tour_result.h"

namespace surface_nbv {

class LinKernighanSolver {
 public:
  struct Config {
    uint64_t seed = 1;
    int restarts = 1;          // independent runs, the best is kept
    int max_trials = -1;       // kicks per restart; -1 = 4 n - 100 clamped to [100, 2000]
    double time_limit_s = 0;   // 0 = no limit (repeatable); else stop at this wall time
    int max_candidates = 6;    // candidate list length
    int max_depth = 7;         // k of the sequential k-opt moves, 3..8
    int or_opt_max_segment = 3;  // Or-opt moves segments of 1..this many (ATSP) nodes
    int kick_segment = 0;      // double-bridge segments of at most this many (ATSP) nodes; 0 = n / 3
    int exact_max_nodes = 12;  // Held-Karp at or below this n (0..13); 0 = LK for every n > 4

    Status validate() const;
    std::string print() const;
  };

  LinKernighanSolver() = default;
  explicit LinKernighanSolver(const Config& config) : config_(config) {}
  const Config& config() const { return config_; }

  // A closed tour starting at node 0 (the cost includes last -> first).
  TourResult solve(const CostMatrix& costs) const;

 private:
  Config config_;
};

}  // namespace surface_nbv
