#include "surface_nbv/eval/error_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace surface_nbv {

double quantileSorted(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double at = std::clamp(q, 0.0, 1.0) * (sorted.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(at));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (at - lo) * (sorted[hi] - sorted[lo]);
}

ErrorStats ErrorStats::of(const std::vector<float>& errors) {
  std::vector<double> values, magnitudes;
  for (const float e : errors) {
    if (std::isfinite(e)) values.push_back(e);
  }
  ErrorStats s;
  s.count = values.size();
  double sum = 0.0, sum_abs = 0.0, sum_sq = 0.0;
  for (const double v : values) sum += v, sum_abs += std::abs(v);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  s.mean = s.count > 0 ? sum / s.count : nan;
  for (const double v : values) sum_sq += (v - s.mean) * (v - s.mean);
  s.std_dev = s.count > 0 ? std::sqrt(sum_sq / s.count) : nan;
  s.rmse = std::hypot(s.mean, s.std_dev);
  s.mean_abs = s.count > 0 ? sum_abs / s.count : nan;
  std::sort(values.begin(), values.end());
  for (const double v : values) magnitudes.push_back(std::abs(v));
  std::sort(magnitudes.begin(), magnitudes.end());
  s.max_abs = magnitudes.empty() ? nan : magnitudes.back();
  s.p5 = quantileSorted(values, 0.05);
  s.p25 = quantileSorted(values, 0.25);
  s.p50 = quantileSorted(values, 0.50);
  s.p75 = quantileSorted(values, 0.75);
  s.p95 = quantileSorted(values, 0.95);
  s.abs_p95 = quantileSorted(magnitudes, 0.95);
  return s;
}

}  // namespace surface_nbv
