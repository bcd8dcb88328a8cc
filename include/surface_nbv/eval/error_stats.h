// Summary figures of a set of signed errors in metres: mean, population
// standard deviation, RMSE (RMSE^2 = mean^2 + std^2), mean absolute error and
// percentiles (linear interpolation between order statistics, as numpy's
// default). Non-finite values are skipped; an empty set gives count 0 and NaN figures.
#pragma once

#include <cstddef>
#include <vector>

namespace surface_nbv {

struct ErrorStats {
  size_t count = 0;
  double mean = 0.0, std_dev = 0.0, rmse = 0.0, mean_abs = 0.0, max_abs = 0.0;
  double p5 = 0.0, p25 = 0.0, p50 = 0.0, p75 = 0.0, p95 = 0.0;  // signed percentiles
  double abs_p95 = 0.0;                                         // 95th percentile of |error|

  static ErrorStats of(const std::vector<float>& errors);
};

// The q-quantile (q in [0, 1]) of sorted finite values.
double quantileSorted(const std::vector<double>& sorted, double q);

}  // namespace surface_nbv
