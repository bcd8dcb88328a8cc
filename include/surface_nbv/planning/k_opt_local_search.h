// Local search on one closed tour of a symmetric cost matrix, the engine of
// LinKernighanSolver: sequential k-opt moves (k = 2 .. max_depth) found by a
// Lin-Kernighan depth-first search over candidate lists with the positive-gain
// rule, Or-opt segment moves, don't-look bits (a queue of active nodes), and
// segment double-bridge kicks. An edge {a, fixed_partner[a]} is never removed
// (the Jonker-Volgenant pair edges; -1 = none). Not thread-safe.
#pragma once

#include <chrono>
#include <cstdint>
#include <random>
#include <vector>

#include "surface_nbv/planning/cost_matrix.h"

namespace surface_nbv {

class KOptLocalSearch {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr int kMaxK = 8;  // deepest sequential move

  // candidates[a]: nodes to try joining to a, best first. `costs` must
  // outlive this. breadth[i]: how many added edges (each passing the
  // positive-gain rule) are tried at level i + 1 of the search; the last
  // entry repeats, empty = 5 at every level.
  KOptLocalSearch(const CostMatrix& costs, std::vector<std::vector<int>> candidates, std::vector<int> fixed_partner,
                  int max_depth, int or_opt_max_segment, std::vector<int> breadth = {});

  // `tour` must be a permutation containing every fixed edge.
  void setTour(const std::vector<int>& tour);
  const std::vector<int>& tour() const { return tour_; }
  double cost() const { return cost_; }

  void activateAll();
  // Applies improving moves until none is left from an active node. Returns
  // false if `deadline` passed first (the tour is still valid).
  bool optimize(Clock::time_point deadline);
  // Non-sequential double bridge on three segments of at most `max_segment`
  // nodes at a random place; activates the changed endpoints. False if the
  // tour is too short for one.
  bool kick(std::mt19937_64* rng, int max_segment);

 private:
  double c(int a, int b) const { return costs_(a, b); }
  int succ(int a) const { return tour_[pos_[a] + 1 == n_ ? 0 : pos_[a] + 1]; }
  int pred(int a) const { return tour_[pos_[a] == 0 ? n_ - 1 : pos_[a] - 1]; }
  bool fixedEdge(int a, int b) const { return fixed_[a] == b; }
  void activate(int a);

  bool improveFrom(int t1);
  bool searchLevel(int level, double gain);
  bool edgeInMove(int a, int b, int pairs, bool removed) const;
  bool orOptFrom(int t1);
  // Replaces the k edges {removed[2i], removed[2i+1]} (tour edges) by the k
  // edges {added[2i], added[2i+1]} if the result is one cycle; gain = removed
  // cost - added cost. Activates every endpoint.
  bool applyMove(const int* removed, const int* added, int k, double gain);

  const CostMatrix& costs_;
  std::vector<std::vector<int>> candidates_;
  std::vector<int> fixed_;
  std::vector<int> breadth_;
  bool all_fixed_ = false;
  int max_depth_, or_opt_max_segment_;
  int n_ = 0;
  std::vector<int> tour_, pos_, buffer_;
  double cost_ = 0.0;
  std::vector<int> queue_;
  size_t queue_head_ = 0;
  std::vector<uint8_t> active_;
  int t_[2 * kMaxK + 2];
};

}  // namespace surface_nbv
