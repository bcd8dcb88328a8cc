// The viewpoint / cluster utility of docs/method.md, in one place: the
// cluster gain (eq. 3), the edge utility f_uv (eq. 5), the two TSP arc costs
// made from it, and eq. 5 for a single viewpoint (the tour-head reranking,
// tour_head.h). ROS-free, header of the surface library.
//
// Why surface and not planning: the gain of eq. 3 is computed by
// ViewpointClusterer in surface_nbv_surface, and surface_nbv_planning links
// surface_nbv_surface (not the other way round; surface must not come to
// depend on planning). Living here, the module is used by both.
//
// Every function is the exact floating expression its callers wrote before,
// in the same order, so that no figure of a mission moves.
#pragma once

#include <cstddef>

namespace surface_nbv {

// Gain of a cluster u (eq. 3): g(u) = |union of C_q over q in u| / |C|, with
// count = |union of C_q| and num_ises = |C|; 0 when num_ises is 0.
double clusterGain(size_t count, size_t num_ises);

// Utility of moving to cluster v (eq. 5):
//   f_uv = g(v) exp(-lambda_tc d(tau_kl) - lambda_ic d(tau_lm)),
// gain = g(v), d_kl the inter-cluster travel from u's exit q_k to v's entry
// q_l, d_lm the intra-cluster path through v.
double edgeUtility(double gain, double d_kl, double d_lm, double lambda_tc, double lambda_ic);

// The tour cost of moving to cluster v (eq. 5): cost = -log f_uv
//   = lambda_tc * d_kl + lambda_ic * d_lm - log g(v), made non-negative by
// adding log(g_max), g_max >= every g(v) > 0, so cost = -log(f_uv / g_max).
// The added constant is the same for every arc into v, so it shifts every
// tour (each node entered once) and every open path from a fixed start (each
// non-start node entered once) by the same amount: the optimal order is
// unchanged. Minimising it maximises the product of the utilities f_uv along
// the tour (objective kProduct of cluster_graph.h). Computed from the terms,
// not as -log(edgeUtility(...)), so that it stays finite where f_uv underflows.
double utilityLogCost(double gain, double d_kl, double d_lm, double lambda_tc, double lambda_ic, double g_max);

// The tour cost that maximises the sum of the utilities instead (objective
// kSum): kSumCostScale * (1 - f_uv / g_max), clamped to [0, kSumCostScale]
// (exactly that range for 0 <= f_uv <= g_max). Every open path from a fixed
// start has one arc per non-start node, so minimising the sum of these costs
// maximises the sum of the f_uv. The scale keeps the differences between
// tours far above the rounding of the Jonker-Volgenant offsets
// (planning/jonker_volgenant.h).
//
// Log and sum cost, side by side: both are decreasing in f_uv and 0 at
// f_uv = g_max; the log cost turns the product of the utilities into a sum
// of arc costs, the sum cost is linear in f_uv itself. So they order single
// arcs alike but whole tours differently: under the log cost the gains drop
// out of a tour (each cluster is entered once) and it is the shortest open
// path in lambda-weighted length; under the sum cost a long hop costs about
// as much as any other long hop, and short hops into high-gain clusters pay.
constexpr double kSumCostScale = 10.0;
double utilitySumCost(double f_uv, double g_max);

// Eq. 5 for one viewpoint q at distance d from the UAV (the tour-head
// reranking, planning/tour_head.h): visible * exp(-lambda d), visible the
// viewpoint's gain (|C_q|, or a caller's weighting of it).
double headUtility(double visible, double distance, double lambda);

}  // namespace surface_nbv
