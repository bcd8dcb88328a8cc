// The outcome of a tour solver: a status (as OMPL's PlannerStatus) and, when
// the status says so, a tour. A tour lists every node once; a closed tour
// returns from the last node to the first, an open path does not.
#pragma once

#include <string>
#include <vector>

#include "surface_nbv/util/status.h"

namespace surface_nbv {

enum class TspStatus {
  kExactSolution,        // optimal, proved (Held-Karp, or n <= 3 enumerated)
  kApproximateSolution,  // best tour of a heuristic that ran its whole budget
  kTimeout,              // the time limit stopped the heuristic; the tour is the best found
  kEmptyInput,           // no node: no tour
  kInvalidInput,         // a cost is NaN, negative, infinite or too large; or the solver config is bad
  kInvalidStart,         // the start node of an open path is not a node
};

const char* toString(TspStatus status);

// True for the statuses that come with a complete, valid tour.
inline bool hasTour(TspStatus status) {
  return status == TspStatus::kExactSolution || status == TspStatus::kApproximateSolution ||
         status == TspStatus::kTimeout;
}

struct TourResult {
  TspStatus status = TspStatus::kInvalidInput;
  std::vector<int> tour;  // empty unless hasTour(status)
  double cost = 0.0;      // closed-tour or open-path cost, matching the call
  int trials = 0;         // heuristic trials (kicks) run, over all restarts
  double seconds = 0.0;   // wall time of the call
  std::string message;    // what was wrong, for the error statuses
};

// What a solver answers before it starts: kInvalidInput with the message when
// `checked` (its validation of the costs and its config) failed, kEmptyInput
// when there is no node. Returns true when it set *result so.
bool refuseInput(const Status& checked, int nodes, TourResult* result);

}  // namespace surface_nbv
