// libFuzzer target: TSPLIB files through readTsplib. An accepted problem must
// have a non-empty square cost matrix of finite, non-negative costs with a
// zero diagonal, symmetric for TYPE TSP, and a type and edge weight type the
// reader supports; a refusal must name the file and a line.
#include <cmath>
#include <string>

#include "fuzz_support.h"
#include "surface_nbv/planning/tsplib_reader.h"

using namespace surface_nbv;
using namespace surface_nbv::fuzz;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static MemoryFile memory;
  const std::string& path = memory.write(data, size);
  TsplibProblem problem;
  const Status s = readTsplib(path, &problem);
  if (!s) {
    FUZZ_CHECK(s.message().rfind(path + ":", 0) == 0, "a refusal that does not name the file: " + s.message());
    return 0;
  }
  const int n = problem.costs.size();
  FUZZ_CHECK(n >= 1, "an accepted problem without nodes");
  FUZZ_CHECK(problem.type == "TSP" || problem.type == "ATSP", problem.type);
  FUZZ_CHECK(problem.edge_weight_type == "EXPLICIT" || problem.edge_weight_type == "EUC_2D", problem.edge_weight_type);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double c = problem.costs(i, j);
      FUZZ_CHECK(std::isfinite(c) && c >= 0.0, "cost " + std::to_string(c));
      if (i == j) FUZZ_CHECK(c == 0.0, "a non-zero diagonal");
      if (problem.type == "TSP") FUZZ_CHECK(c == problem.costs(j, i), "TYPE TSP but asymmetric");
    }
  }
  return 0;
}
