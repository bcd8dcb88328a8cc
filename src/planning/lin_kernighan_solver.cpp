#include "surface_nbv/planning/lin_kernighan_solver.h"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <random>
#include <sstream>

#include "surface_nbv/planning/held_karp.h"
#include "surface_nbv/planning/jonker_volgenant.h"
#include "surface_nbv/planning/k_opt_local_search.h"
#include "surface_nbv/planning/lk_candidates.h"

namespace surface_nbv {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Nearest-neighbour tour from `start` that always takes the fixed partner next when it is unvisited.
std::vector<int> nearestNeighbourTour(const CostMatrix& costs, const std::vector<int>& fixed, int start) {
  const int n = costs.size();
  std::vector<char> seen(n, 0);
  std::vector<int> tour{start};
  seen[start] = 1;
  for (int cur = start; static_cast<int>(tour.size()) < n;) {
    const bool to_partner = fixed[cur] >= 0 && !seen[fixed[cur]];
    int next = to_partner ? fixed[cur] : -1;
    for (int b = 0; b < n && !to_partner; ++b) {
      if (!seen[b] && (next < 0 || costs(cur, b) < costs(cur, next))) next = b;
    }
    seen[next] = 1;
    tour.push_back(next);
    cur = next;
  }
  return tour;
}

struct LkRun {
  std::vector<int> tour;
  double cost = 0.0;
  int trials = 0;
  bool timed_out = false;
};

// Restarts of kick-and-improve on a symmetric matrix; `fixed` pairs are never cut.
LkRun runLk(const CostMatrix& costs, const std::vector<int>& fixed, std::vector<std::vector<int>> candidates,
            std::vector<int> breadth, int trials_per_restart, int or_opt_segment, int kick_segment,
            const LinKernighanSolver::Config& config, Clock::time_point deadline) {
  const int n = costs.size();
  KOptLocalSearch search(costs, std::move(candidates), fixed, config.max_depth, or_opt_segment, std::move(breadth));
  std::mt19937_64 rng(config.seed);
  LkRun best;
  for (int restart = 0; restart < config.restarts && !best.timed_out; ++restart) {
    search.setTour(nearestNeighbourTour(costs, fixed, static_cast<int>(rng() % n)));
    search.activateAll();
    bool in_time = search.optimize(deadline);
    std::vector<int> kept = search.tour();
    double kept_cost = search.cost();
    for (int trial = 0; trial < trials_per_restart && in_time; ++trial) {
      if (!search.kick(&rng, kick_segment)) break;
      ++best.trials;
      in_time = search.optimize(deadline) && Clock::now() <= deadline;
      if (search.cost() <= kept_cost + 1e-9) {
        kept = search.tour();
        kept_cost = search.cost();
      } else {
        search.setTour(kept);
      }
    }
    if (best.tour.empty() || kept_cost < best.cost) {
      best.tour = kept;
      best.cost = kept_cost;
    }
    best.timed_out = !in_time;
  }
  return best;
}

void rotateToZero(std::vector<int>* tour) {
  const auto it = std::find(tour->begin(), tour->end(), 0);
  std::rotate(tour->begin(), it, tour->end());
}

}  // namespace

Status LinKernighanSolver::Config::validate() const {
  if (restarts < 1) return Status::Error("restarts expected >= 1");
  if (max_trials < -1) return Status::Error("max_trials expected >= -1");
  if (!(time_limit_s >= 0)) return Status::Error("time_limit_s expected >= 0");
  if (max_candidates < 2) return Status::Error("max_candidates expected >= 2");
  if (max_depth < 3 || max_depth > KOptLocalSearch::kMaxK)
    return Status::Error("max_depth expected in [3, " + std::to_string(KOptLocalSearch::kMaxK) + "]");
  if (or_opt_max_segment < 0) return Status::Error("or_opt_max_segment expected >= 0");
  if (kick_segment < 0) return Status::Error("kick_segment expected >= 0");
  if (exact_max_nodes < 0 || exact_max_nodes > kHeldKarpMaxNodes)
    return Status::Error("exact_max_nodes expected in [0, " + std::to_string(kHeldKarpMaxNodes) + "]");
  return Status::Ok();
}

std::string LinKernighanSolver::Config::print() const {
  std::ostringstream ss;
  ss << "seed " << seed << ", restarts " << restarts << ", max_trials " << max_trials << ", time_limit_s "
     << time_limit_s << ", max_candidates " << max_candidates << ", max_depth " << max_depth
     << ", or_opt_max_segment " << or_opt_max_segment << ", kick_segment " << kick_segment << ", exact_max_nodes "
     << exact_max_nodes;
  return ss.str();
}

TourResult LinKernighanSolver::solve(const CostMatrix& costs) const {
  const Clock::time_point t0 = Clock::now();
  TourResult r;
  const int n = costs.size();
  Status s = config_.validate();
  if (s) s = costs.validate();
  if (refuseInput(s, n, &r)) return r;
  if (n <= std::max(4, config_.exact_max_nodes)) {  // LK needs 5 nodes for a 3-opt move
    r = heldKarp(costs);
    r.seconds = secondsSince(t0);
    return r;
  }
  const Clock::time_point deadline =
      config_.time_limit_s > 0 ? t0 + std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(config_.time_limit_s))
                               : Clock::time_point::max();
  const int trials = config_.max_trials >= 0 ? config_.max_trials : std::max(100, std::min(4 * n - 100, 2000));
  const int kick_segment = config_.kick_segment > 0 ? config_.kick_segment : n;
  LkRun run;
  if (costs.isSymmetric()) {
    const std::vector<int> fixed(n, -1);
    run = runLk(costs, fixed, nearestCandidates(costs, fixed, CostMatrix::kMaxCost * 2, config_.max_candidates),
                {5, 5, 3, 2, 1}, trials, config_.or_opt_max_segment, kick_segment, config_, deadline);
    r.tour = run.tour;
  } else {
    const JvTransform jv = jonkerVolgenant(costs, 0.0);
    std::vector<int> fixed(2 * n);
    for (int i = 0; i < n; ++i) {
      fixed[i] = n + i;
      fixed[n + i] = i;
    }
    // Every candidate on the first four levels (the 3- and 5-opt moves), then
    // a narrow search for the 7-opt ones.
    const int all = config_.max_candidates;
    run = runLk(jv.symmetric, fixed, assignmentCandidates(costs, all), {all, all, all, all, 2, 1}, trials,
                2 * config_.or_opt_max_segment, 2 * kick_segment, config_, deadline);
    if (!symmetricToAtspTour(run.tour, n, &r.tour)) {
      r.status = TspStatus::kInvalidInput;
      r.message = "internal error: the symmetric tour lost a Jonker-Volgenant pair edge";
      return r;
    }
  }
  rotateToZero(&r.tour);
  r.cost = costs.tourCost(r.tour);
  r.trials = run.trials;
  r.status = run.timed_out ? TspStatus::kTimeout : TspStatus::kApproximateSolution;
  r.seconds = secondsSince(t0);
  return r;
}

}  // namespace surface_nbv
