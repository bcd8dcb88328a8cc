// The cluster graph G = (U, E, a_uv) of docs/method.md "Cluster graph and tour"
// (eq. 4, 5) and the tour over it. ROS-free.
//
// Nodes: node 0 is the UAV's current configuration, node u > 0 is cluster u - 1
// of the Frontier. Edge u -> v (v > 0, u != v) carries the 6-tuple
// (tau_kl, tau_lm, g(v), d(tau_kl), d(tau_lm), f_uv):
//   q_k    the exit configuration of u (see below),
//   q_l    the viewpoint of v closest to q_k by path length (ties: lowest
//          position in v's viewpoint list),
//   tau_lm the shortest Hamiltonian path through v's viewpoints starting at q_l
//          (end q_m free): exact (Held-Karp over subsets) for <= kExactClusterSize
//          viewpoints, nearest neighbour + 2-opt otherwise,
//   f_uv   = g(v) exp(-lambda_tc d_kl - lambda_ic d_lm)   (eq. 5, edgeUtility),
//   cost   = utilityLogCost(...) = -log f_uv + log g_max >= 0, the TSP arc cost
//            (objective kProduct), or utilitySumCost(f_uv, g_max) =
//            kSumCostScale (1 - f_uv / g_max) (objective kSum); both in
//            surface/viewpoint_utility.h.
//
// Simplification (documented, deliberate): in a pairwise graph the way u was
// entered is not known, so u's exit is fixed per cluster: q_k = the end of u's
// intra-cluster path from its *best* entry (the entry whose Hamiltonian path is
// shortest; ties: lowest position). For node 0, q_k is the UAV itself. The tour
// flies each cluster along the tau_lm of the edge used to enter it, so the real
// hop between two clusters starts at that path's end, which may differ from the
// nominal q_k; TourPlan::flight_length measures the real flight.
//
// Distances come from an oracle (path length, +inf when no path); 2-opt assumes
// it is symmetric. An edge is reachable when d_kl and d_lm are both finite,
// an unreachable edge, or one into a cluster of gain <= 0, costs
// CostMatrix::kUnreachable and has utility 0. Arcs into node 0 cost 0 (open path).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "surface_nbv/planning/cost_matrix.h"
#include "surface_nbv/planning/lin_kernighan_solver.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// What the tour maximises over its arcs. kProduct: the product of the
// utilities f_uv (arc cost -log f_uv); each cluster is entered once, so the
// gains drop out and the tour is the shortest open path in lambda-weighted
// length. kSum: their sum, the paper's "total utility" (arc cost
// proportional to g_max - f_uv); a long hop costs about as much as any
// other long hop, and short hops into clusters of high gain pay most.
enum class TourObjective { kProduct, kSum };

const char* toString(TourObjective objective);
// "product" or "sum"; false for anything else.
bool parseTourObjective(const std::string& text, TourObjective* objective);

struct ClusterGraphConfig {
  double lambda_tc = 0.3;   // weight of the inter-cluster travel d(tau_kl), 1/m
  double lambda_ic = 0.03;  // weight of the intra-cluster travel d(tau_lm), 1/m
  TourObjective objective = TourObjective::kProduct;

  // Both finite and >= 0.
  Status validate() const;
};

// Path length between two positions; +inf (or any non-finite value) = no path.
using DistanceFn = std::function<double(const Eigen::Vector3d&, const Eigen::Vector3d&)>;

// Clusters of at most this many viewpoints get the exact intra-cluster path.
constexpr int kExactClusterSize = 8;

struct ClusterEdge {
  int from = -1, to = -1;                 // graph nodes
  Eigen::Vector4d q_k = Eigen::Vector4d::Zero();  // tau_kl start: exit of `from`
  int32_t k_viewpoint = -1;               // frontier index of q_k; -1 for the UAV
  uint32_t l_viewpoint = 0;               // frontier index of q_l (tau_kl end)
  std::vector<uint32_t> tau_lm;           // frontier indices, front = q_l, back = q_m
  double gain = 0.0;                      // g(v)
  double d_kl = 0.0, d_lm = 0.0;          // d(tau_kl), d(tau_lm); +inf when no path
  double utility = 0.0;                   // f_uv (eq. 5); 0 when unreachable
  double cost = CostMatrix::kUnreachable; // TSP arc cost
  bool reachable = false;                 // d_kl and d_lm finite
};

class ClusterGraph {
 public:
  // Builds every edge (O(nodes * viewpoints) oracle calls plus the pairwise
  // distances inside each cluster). On bad input (invalid config, no oracle,
  // empty cluster, viewpoint index out of range) status() is an error and the
  // graph has no node.
  ClusterGraph(const Frontier& frontier, const Eigen::Vector4d& uav, const DistanceFn& distance,
               const ClusterGraphConfig& config = ClusterGraphConfig());

  const Status& status() const { return status_; }
  int nodeCount() const { return nodes_; }                 // clusters + 1, or 0 on error
  int clusterCount() const { return nodes_ > 0 ? nodes_ - 1 : 0; }
  // Edge u -> v; requires v > 0, u != v, both < nodeCount().
  const ClusterEdge& edge(int u, int v) const { return edges_[size_t(u) * nodes_ + v]; }
  const CostMatrix& costs() const { return costs_; }
  const Eigen::Vector4d& uav() const { return uav_; }
  // [x, y, z, yaw] of a frontier viewpoint.
  Eigen::Vector4d configuration(uint32_t viewpoint) const;
  const DistanceFn& distance() const { return distance_; }

 private:
  Status status_;
  int nodes_ = 0;
  Eigen::Vector4d uav_ = Eigen::Vector4d::Zero();
  std::vector<Eigen::Vector4d> configs_;  // per frontier viewpoint
  std::vector<ClusterEdge> edges_;        // nodes_ x nodes_, row = from
  CostMatrix costs_;
  DistanceFn distance_;
};

enum class TourPlanStatus {
  kOk,                  // order covers every reachable cluster of positive gain
  kNothingToDo,         // the frontier has no cluster
  kNoReachableCluster,  // clusters exist, none reachable with positive gain
  kInvalidGraph,        // the graph failed to build
  kSolverFailed,        // the TSP solver returned no tour (see message)
};

const char* toString(TourPlanStatus status);

struct TourPlan {
  TourPlanStatus status = TourPlanStatus::kInvalidGraph;
  std::vector<int> clusters;                    // cluster indices, visit order
  std::vector<uint32_t> viewpoints;             // frontier indices, flight order
  std::vector<Eigen::Vector4d> configurations;  // [x, y, z, yaw] of `viewpoints`
  std::vector<int> unreachable;                 // clusters left out: no path
  std::vector<int> no_gain;                     // clusters left out: gain <= 0
  double cost = 0.0;                            // sum of the arc costs used
  double utility = 0.0;                         // sum of f_uv of the arcs used
  double flight_length = 0.0;                   // oracle length UAV -> viewpoints in order
  TspStatus tsp_status = TspStatus::kEmptyInput;
  std::string message;
};

// The open path from the UAV through every reachable cluster of positive gain,
// minimising the summed arc costs (solveOpenPath on the reachable sub-matrix).
// A cluster is reachable when the edge 0 -> v is. Should the solved order still
// need an unreachable arc, the order stops there and the rest are reported
// in `unreachable`.
TourPlan planTour(const ClusterGraph& graph,
                  const LinKernighanSolver::Config& config = LinKernighanSolver::Config());

}  // namespace surface_nbv
