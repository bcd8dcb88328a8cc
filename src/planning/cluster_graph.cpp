#include "surface_nbv/planning/cluster_graph.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surface_nbv/planning/open_path.h"
#include "surface_nbv/surface/viewpoint_utility.h"

namespace surface_nbv {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Oracle output with every non-finite or negative value mapped to +inf.
double safeDistance(const DistanceFn& distance, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double d = distance(a, b);
  return std::isfinite(d) && d >= 0.0 ? d : kInf;
}

using Matrix = std::vector<std::vector<double>>;

double pathLength(const Matrix& d, const std::vector<int>& path) {
  double sum = 0.0;
  for (size_t i = 1; i < path.size(); ++i) sum += d[path[i - 1]][path[i]];
  return sum;
}

// Shortest open path from `start` through all n nodes, free end: Held-Karp over
// subsets. Requires n <= kExactClusterSize. +inf arcs are allowed.
std::vector<int> exactPath(const Matrix& d, int start) {
  const int n = static_cast<int>(d.size());
  const size_t full = size_t(1) << n;
  std::vector<double> dp(full * n, kInf);
  std::vector<int> parent(full * n, -1);
  dp[(size_t(1) << start) * n + start] = 0.0;
  for (size_t mask = 1; mask < full; ++mask) {
    for (int j = 0; j < n; ++j) {
      const double here = dp[mask * n + j];
      if (!(mask >> j & 1) || here == kInf) continue;
      for (int k = 0; k < n; ++k) {
        if (mask >> k & 1) continue;
        const size_t next = (mask | size_t(1) << k) * n + k;
        if (here + d[j][k] < dp[next]) {
          dp[next] = here + d[j][k];
          parent[next] = j;
        }
      }
    }
  }
  const size_t all = full - 1;
  int end = start == 0 && n > 1 ? 1 : 0;
  for (int j = 0; j < n; ++j)
    if (j != start && dp[all * n + j] < dp[all * n + end]) end = j;
  if (n == 1) end = start;
  if (dp[all * n + end] == kInf) {  // no finite path: visit in index order from start
    std::vector<int> order{start};
    for (int j = 0; j < n; ++j)
      if (j != start) order.push_back(j);
    return order;
  }
  std::vector<int> path;
  size_t mask = all;
  for (int j = end; j != -1;) {
    path.push_back(j);
    const int p = parent[mask * n + j];
    mask &= ~(size_t(1) << j);
    j = p;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

// Nearest neighbour from `start`, then 2-opt (segment reversal; assumes d is
// symmetric) until no finite improvement remains. Start stays first.
std::vector<int> heuristicPath(const Matrix& d, int start) {
  const int n = static_cast<int>(d.size());
  std::vector<int> path{start};
  std::vector<bool> used(n, false);
  used[start] = true;
  for (int step = 1; step < n; ++step) {
    int best = -1;
    for (int k = 0; k < n; ++k)
      if (!used[k] && (best < 0 || d[path.back()][k] < d[path.back()][best])) best = k;
    used[best] = true;
    path.push_back(best);
  }
  for (bool improved = true; improved;) {
    improved = false;
    for (int i = 1; i + 1 < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        const bool tail = j + 1 < n;
        const double before = d[path[i - 1]][path[i]] + (tail ? d[path[j]][path[j + 1]] : 0.0);
        const double after = d[path[i - 1]][path[j]] + (tail ? d[path[i]][path[j + 1]] : 0.0);
        if (std::isfinite(after) && after < before - 1e-12) {
          std::reverse(path.begin() + i, path.begin() + j + 1);
          improved = true;
        }
      }
    }
  }
  return path;
}

// Per cluster: the intra-cluster path and its length from every entry, and the
// best entry (shortest path; ties: lowest position).
struct IntraPaths {
  std::vector<std::vector<uint32_t>> path;  // frontier indices, per entry position
  std::vector<double> length;
  size_t best = 0;
};

IntraPaths intraPaths(const Cluster& cluster, const std::vector<Eigen::Vector4d>& configs,
                      const DistanceFn& distance) {
  const size_t n = cluster.viewpoints.size();
  Matrix d(n, std::vector<double>(n, 0.0));
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j)
      if (i != j)
        d[i][j] = safeDistance(distance, configs[cluster.viewpoints[i]].head<3>(),
                               configs[cluster.viewpoints[j]].head<3>());
  IntraPaths out;
  for (size_t s = 0; s < n; ++s) {
    const std::vector<int> local =
        n <= size_t(kExactClusterSize) ? exactPath(d, int(s)) : heuristicPath(d, int(s));
    std::vector<uint32_t> global;
    for (int i : local) global.push_back(cluster.viewpoints[i]);
    out.path.push_back(std::move(global));
    out.length.push_back(pathLength(d, local));
    if (out.length[s] < out.length[out.best]) out.best = s;
  }
  return out;
}

}  // namespace

const char* toString(TourObjective objective) {
  return objective == TourObjective::kSum ? "sum" : "product";
}

bool parseTourObjective(const std::string& text, TourObjective* objective) {
  if (text == "product") {
    *objective = TourObjective::kProduct;
  } else if (text == "sum") {
    *objective = TourObjective::kSum;
  } else {
    return false;
  }
  return true;
}

Status ClusterGraphConfig::validate() const {
  if (!std::isfinite(lambda_tc) || lambda_tc < 0.0) return Status::Error("lambda_tc must be finite and >= 0");
  if (!std::isfinite(lambda_ic) || lambda_ic < 0.0) return Status::Error("lambda_ic must be finite and >= 0");
  return Status::Ok();
}

ClusterGraph::ClusterGraph(const Frontier& frontier, const Eigen::Vector4d& uav, const DistanceFn& distance,
                           const ClusterGraphConfig& config)
    : uav_(uav), distance_(distance) {
  status_ = config.validate();
  if (status_ && !distance) status_ = Status::Error("no distance oracle");
  for (size_t c = 0; status_ && c < frontier.clusters.size(); ++c) {
    if (frontier.clusters[c].viewpoints.empty()) status_ = Status::Error("cluster " + std::to_string(c) + " is empty");
    for (uint32_t v : frontier.clusters[c].viewpoints)
      if (v >= frontier.viewpoints.size())
        status_ = Status::Error("cluster " + std::to_string(c) + " names viewpoint " + std::to_string(v));
  }
  if (!status_) return;
  for (const Viewpoint& v : frontier.viewpoints) configs_.emplace_back(v.position.x(), v.position.y(), v.position.z(), v.yaw);

  const int clusters = static_cast<int>(frontier.clusters.size());
  nodes_ = clusters + 1;
  std::vector<IntraPaths> intra;
  double g_max = 0.0;
  for (const Cluster& c : frontier.clusters) {
    intra.push_back(intraPaths(c, configs_, distance_));
    if (std::isfinite(c.gain)) g_max = std::max(g_max, c.gain);
  }
  edges_.assign(size_t(nodes_) * nodes_, ClusterEdge());
  costs_ = CostMatrix(nodes_, 0.0);
  for (int u = 0; u < nodes_; ++u) {
    Eigen::Vector4d q_k = uav_;
    int32_t k_viewpoint = -1;
    if (u > 0) {
      const IntraPaths& from = intra[u - 1];
      k_viewpoint = static_cast<int32_t>(from.path[from.best].back());
      q_k = configs_[k_viewpoint];
    }
    for (int v = 1; v < nodes_; ++v) {
      if (v == u) continue;
      const Cluster& to = frontier.clusters[v - 1];
      ClusterEdge& e = edges_[size_t(u) * nodes_ + v];
      e.from = u;
      e.to = v;
      e.q_k = q_k;
      e.k_viewpoint = k_viewpoint;
      e.gain = to.gain;
      size_t entry = 0;
      e.d_kl = kInf;
      for (size_t i = 0; i < to.viewpoints.size(); ++i) {
        const double d = safeDistance(distance_, q_k.head<3>(), configs_[to.viewpoints[i]].head<3>());
        if (d < e.d_kl) {
          e.d_kl = d;
          entry = i;
        }
      }
      e.l_viewpoint = to.viewpoints[entry];
      e.tau_lm = intra[v - 1].path[entry];
      e.d_lm = intra[v - 1].length[entry];
      e.reachable = std::isfinite(e.d_kl) && std::isfinite(e.d_lm);
      if (e.reachable && std::isfinite(e.gain) && e.gain > 0.0) {
        e.utility = edgeUtility(e.gain, e.d_kl, e.d_lm, config.lambda_tc, config.lambda_ic);
        e.cost = config.objective == TourObjective::kSum
                     ? utilitySumCost(e.utility, g_max)
                     : std::min(CostMatrix::kUnreachable,
                                utilityLogCost(e.gain, e.d_kl, e.d_lm, config.lambda_tc, config.lambda_ic, g_max));
      }
      costs_.at(u, v) = e.cost;
    }
  }
}

Eigen::Vector4d ClusterGraph::configuration(uint32_t viewpoint) const { return configs_.at(viewpoint); }

const char* toString(TourPlanStatus status) {
  switch (status) {
    case TourPlanStatus::kOk: return "ok";
    case TourPlanStatus::kNothingToDo: return "nothing to do (no cluster)";
    case TourPlanStatus::kNoReachableCluster: return "no reachable cluster with positive gain";
    case TourPlanStatus::kInvalidGraph: return "invalid cluster graph";
    case TourPlanStatus::kSolverFailed: return "tour solver failed";
  }
  return "unknown";
}

TourPlan planTour(const ClusterGraph& graph, const LinKernighanSolver::Config& config) {
  TourPlan plan;
  if (!graph.status()) {
    plan.message = graph.status().message();
    return plan;
  }
  std::vector<int> nodes{0};  // sub-problem node -> graph node
  for (int v = 1; v < graph.nodeCount(); ++v) {
    const ClusterEdge& e = graph.edge(0, v);
    if (!e.reachable)
      plan.unreachable.push_back(v - 1);
    else if (!(e.gain > 0.0) || !std::isfinite(e.gain))
      plan.no_gain.push_back(v - 1);
    else
      nodes.push_back(v);
  }
  if (graph.clusterCount() == 0) {
    plan.status = TourPlanStatus::kNothingToDo;
    return plan;
  }
  if (nodes.size() == 1) {
    plan.status = TourPlanStatus::kNoReachableCluster;
    return plan;
  }
  const int n = static_cast<int>(nodes.size());
  CostMatrix sub(n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = 1; j < n; ++j)
      if (i != j) sub.at(i, j) = graph.costs()(nodes[i], nodes[j]);
  const TourResult r = solveOpenPath(sub, 0, config);
  plan.tsp_status = r.status;
  if (!hasTour(r.status)) {
    plan.status = TourPlanStatus::kSolverFailed;
    plan.message = r.message;
    return plan;
  }
  Eigen::Vector3d at = graph.uav().head<3>();
  for (size_t i = 1; i < r.tour.size(); ++i) {
    const ClusterEdge& e = graph.edge(nodes[r.tour[i - 1]], nodes[r.tour[i]]);
    if (!e.reachable) {  // the order cannot continue: report the rest
      for (size_t j = i; j < r.tour.size(); ++j) plan.unreachable.push_back(nodes[r.tour[j]] - 1);
      break;
    }
    plan.clusters.push_back(e.to - 1);
    plan.cost += e.cost;
    plan.utility += e.utility;
    for (uint32_t vp : e.tau_lm) {
      const Eigen::Vector4d q = graph.configuration(vp);
      plan.flight_length += safeDistance(graph.distance(), at, q.head<3>());
      at = q.head<3>();
      plan.viewpoints.push_back(vp);
      plan.configurations.push_back(q);
    }
  }
  std::sort(plan.unreachable.begin(), plan.unreachable.end());
  plan.status = TourPlanStatus::kOk;
  return plan;
}

}  // namespace surface_nbv
