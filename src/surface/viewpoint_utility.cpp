#include "surface_nbv/surface/viewpoint_utility.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {

double clusterGain(size_t count, size_t num_ises) {
  return num_ises > 0 ? static_cast<double>(count) / static_cast<double>(num_ises) : 0.0;
}

double edgeUtility(double gain, double d_kl, double d_lm, double lambda_tc, double lambda_ic) {
  return gain * std::exp(-lambda_tc * d_kl - lambda_ic * d_lm);
}

double utilityLogCost(double gain, double d_kl, double d_lm, double lambda_tc, double lambda_ic, double g_max) {
  return lambda_tc * d_kl + lambda_ic * d_lm - std::log(gain) + std::log(g_max);
}

double utilitySumCost(double f_uv, double g_max) {
  return kSumCostScale * std::clamp(1.0 - f_uv / g_max, 0.0, 1.0);
}

double headUtility(double visible, double distance, double lambda) { return visible * std::exp(-lambda * distance); }

}  // namespace surface_nbv
