// Reads a TSPLIB file: TYPE TSP or ATSP; EDGE_WEIGHT_TYPE EXPLICIT with
// EDGE_WEIGHT_FORMAT FULL_MATRIX (EDGE_WEIGHT_SECTION), or EUC_2D with a
// NODE_COORD_SECTION (distance = nint(euclidean), as TSPLIB defines it).
// The diagonal is set to 0. Anything else, or a malformed file, is refused
// with a message "FILE:LINE: what is wrong".
#pragma once

#include <string>

#include "surface_nbv/planning/cost_matrix.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct TsplibProblem {
  std::string name;
  std::string type;              // "TSP" or "ATSP"
  std::string edge_weight_type;  // "EXPLICIT" or "EUC_2D"
  CostMatrix costs;
};

Status readTsplib(const std::string& path, TsplibProblem* problem);

}  // namespace surface_nbv
