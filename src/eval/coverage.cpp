#include "surface_nbv/eval/coverage.h"

#include <algorithm>
#include <limits>

#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {

CoverageResult computeCoverage(const SurfaceCloud& ground_truth, const std::vector<uint8_t>& visible,
                               const PointIndex& reconstruction, double e_max, int threads) {
  constexpr size_t kChunk = 4096;
  const size_t n = ground_truth.size();
  CoverageResult result;
  result.nearest.assign(n, std::numeric_limits<float>::quiet_NaN());
  result.covered.assign(n, 0);
  parallelFor((n + kChunk - 1) / kChunk, threads, [&](size_t chunk) {
    const size_t end = std::min(n, (chunk + 1) * kChunk);
    for (size_t i = chunk * kChunk; i < end; ++i) {
      int index = -1;
      float distance = 0.0f;
      if (visible[i] == 0 || !reconstruction.nearest(ground_truth.points[i], &index, &distance)) continue;
      result.nearest[i] = distance;
      result.covered[i] = distance <= e_max ? 1 : 0;
    }
  });
  for (size_t i = 0; i < n; ++i) {
    result.visible += visible[i] != 0 ? 1 : 0;
    result.num_covered += result.covered[i];
  }
  return result;
}

}  // namespace surface_nbv
