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

bool refuseInput(const Status& checked, int nodes, TourResult* result) {
  if (!checked) {
    result->status = TspStatus::kInvalidInput;
    result->message = checked.message();
    return true;
  }
  if (nodes == 0) {
    result->status = TspStatus::kEmptyInput;
    result->message = "no node";
    return true;
  }
  return false;
}

}  // namespace surface_nbv
