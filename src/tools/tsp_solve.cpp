// tsp_solve: solves a TSPLIB instance (TSP or ATSP; EXPLICIT FULL_MATRIX or
// EUC_2D) as a closed tour with LinKernighanSolver and prints
//   tour_length: N      (its own line)
//   time: S s
//   status: exact | approximate | timeout
// Exit 0 with a tour, 2 for bad arguments or a bad file, 1 for a failure.
//
//   tsp_solve FILE [--seed N] [--time-limit S] [--runs N] [--trials N] [--print-tour]
#include <cstdio>
#include <iostream>

#include "surface_nbv/planning/lin_kernighan_solver.h"
#include "surface_nbv/planning/tsplib_reader.h"
#include "surface_nbv/util/cli_args.h"

using namespace surface_nbv;

int main(int argc, char** argv) {
  CliArgs args({"seed", "time-limit", "runs", "trials"}, {"print-tour", "help"});
  if (Status s = args.parse(argc, argv); !s) {
    std::cerr << "tsp_solve: " << s.message() << "\n";
    return 2;
  }
  if (args.has("help") || args.positional().size() != 1) {
    (args.has("help") ? std::cout : std::cerr)
        << "usage: tsp_solve FILE [--seed N] [--time-limit S] [--runs N] [--trials N] [--print-tour]\n";
    return args.has("help") ? 0 : 2;
  }
  LinKernighanSolver::Config config;
  int seed = 1;
  Status s = args.getInt("seed", &seed);
  if (s) s = args.getDouble("time-limit", &config.time_limit_s);
  if (s) s = args.getInt("runs", &config.restarts);
  if (s) s = args.getInt("trials", &config.max_trials);
  if (s && seed < 0) s = Status::Error("--seed expects a non-negative integer");
  if (s) s = config.validate();
  if (!s) {
    std::cerr << "tsp_solve: " << s.message() << "\n";
    return 2;
  }
  config.seed = static_cast<uint64_t>(seed);
  TsplibProblem problem;
  if (Status read = readTsplib(args.positional()[0], &problem); !read) {
    std::cerr << "tsp_solve: " << read.message() << "\n";
    return 2;
  }
  const TourResult r = LinKernighanSolver(config).solve(problem.costs);
  std::printf("name: %s\ntype: %s, %d nodes, %s\n", problem.name.c_str(), problem.type.c_str(),
              problem.costs.size(), problem.edge_weight_type.c_str());
  if (!hasTour(r.status)) {
    std::printf("status: %s\n", toString(r.status));
    std::cerr << "tsp_solve: " << r.message << "\n";
    return 1;
  }
  std::printf("tour_length: %.15g\ntime: %.6f s\nstatus: %s\ntrials: %d\n", r.cost, r.seconds, toString(r.status),
              r.trials);
  if (args.has("print-tour")) {
    std::printf("tour:");
    for (int v : r.tour) std::printf(" %d", v + 1);
    std::printf("\n");
  }
  return 0;
}
