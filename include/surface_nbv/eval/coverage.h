// Coverage of the ground truth (docs/method.md, "Evaluation protocol"): a visible
// ground-truth sample is covered when a reconstructed sample lies within
// e_max = rho_v sqrt(3) / 2 of it; coverage = covered / visible.
#pragma once

#include <cstdint>
#include <vector>

#include "surface_nbv/eval/point_index.h"
#include "surface_nbv/eval/surface_sampler.h"

namespace surface_nbv {

struct CoverageResult {
  // Per ground-truth sample: distance to the nearest reconstructed sample
  // (NaN when hidden or nothing to find), and whether it is within e_max.
  std::vector<float> nearest;
  std::vector<uint8_t> covered;
  size_t visible = 0, num_covered = 0;

  double coverage() const { return visible > 0 ? static_cast<double>(num_covered) / visible : 0.0; }
};

// Samples with visible[i] == 0 are skipped. Repeats exactly whatever `threads`.
CoverageResult computeCoverage(const SurfaceCloud& ground_truth, const std::vector<uint8_t>& visible,
                               const PointIndex& reconstruction, double e_max, int threads);

}  // namespace surface_nbv
