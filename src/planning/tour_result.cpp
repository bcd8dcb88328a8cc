#include "surface_nbv/planning/tour_result.h"

namespace surface_nbv {

const char* toString(TspStatus status) {
  switch (status) {
    case TspStatus::kExactSolution: return "exact";
    case TspStatus::kApproximateSolution: return "approximate";
    case TspStatus::kTimeout: return "timeout";
    case TspStatus::kEmptyInput: return "empty input";
    case TspStatus::kInvalidInput: return "invalid input";
    case TspStatus::kInvalidStart: return "invalid start";
  }
  return "unknown";
}

}  // namespace surface_nbv
