#include "surface_nbv/planning/tour_head.h"

#include <algorithm>

#include "surface_nbv/surface/viewpoint_utility.h"

namespace surface_nbv {

size_t bestTourHead(const std::vector<Eigen::Vector4d>& tour, const Eigen::Vector4d& uav, size_t lookahead,
                    double lambda, double vertical_scale, const std::function<double(const Eigen::Vector4d&)>& gain) {
  const size_t n = std::min(tour.size(), lookahead);
  size_t best = 0;
  double best_utility = -1.0;
  for (size_t i = 0; i < n; ++i) {
    const double visible = gain(tour[i]);
    Eigen::Vector3d delta = tour[i].head<3>() - uav.head<3>();
    delta.z() *= vertical_scale;
    const double utility = headUtility(visible, delta.norm(), lambda);
    if (utility > best_utility) best = i, best_utility = utility;
  }
  return best;
}

}  // namespace surface_nbv
