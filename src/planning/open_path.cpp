#include "surface_nbv/planning/open_path.h"

#include <algorithm>
#include <chrono>

namespace surface_nbv {

TourResult solveOpenPath(const CostMatrix& costs, int start, const LinKernighanSolver::Config& config) {
  const auto t0 = std::chrono::steady_clock::now();
  const int n = costs.size();
  TourResult r;
  if (refuseInput(Status::Ok(), n, &r)) return r;  // the solver checks the costs
  if (start < 0 || start >= n) {
    r.status = TspStatus::kInvalidStart;
    r.message = "start node " + std::to_string(start) + " is not in [0, " + std::to_string(n) + ")";
    return r;
  }
  CostMatrix closed = costs;
  for (int i = 0; i < n; ++i) closed.at(i, start) = 0.0;
  r = LinKernighanSolver(config).solve(closed);
  if (!hasTour(r.status)) return r;
  std::rotate(r.tour.begin(), std::find(r.tour.begin(), r.tour.end(), start), r.tour.end());
  r.cost = costs.pathCost(r.tour);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace surface_nbv
