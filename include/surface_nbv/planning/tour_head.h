// Tour-head reranking (ExplorerConfig::head_lookahead): of the first
// `lookahead` viewpoints of the tour, the one with the best eq. 5 utility for a
// single viewpoint, headUtility(gain(q), d, lambda) = gain(q) exp(-lambda d)
// (surface/viewpoint_utility.h), d the straight distance from the UAV measured
// as sqrt(dx^2 + dy^2 + (vertical_scale dz)^2). ROS-free.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include <Eigen/Core>

namespace surface_nbv {

// The index in [0, min(lookahead, tour.size())) of the best viewpoint; ties
// go to the earliest. 0 when the tour is empty, lookahead is 0 or no utility
// is above -1 (NaN ones never win).
size_t bestTourHead(const std::vector<Eigen::Vector4d>& tour, const Eigen::Vector4d& uav, size_t lookahead,
                    double lambda, double vertical_scale, const std::function<double(const Eigen::Vector4d&)>& gain);

}  // namespace surface_nbv
