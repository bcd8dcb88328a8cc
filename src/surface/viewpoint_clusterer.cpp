#include "surface_nbv/surface/viewpoint_clusterer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "surface_nbv/surface/point_grid.h"
#include "surface_nbv/surface/viewpoint_utility.h"

#include "surface_nbv/surface/chunked_for.h"

namespace surface_nbv {
namespace {

int findRoot(std::vector<int>* parent, int i) {
  while ((*parent)[i] != i) {
    (*parent)[i] = (*parent)[(*parent)[i]];
    i = (*parent)[i];
  }
  return i;
}

}  // namespace

bool ViewpointClusterer::segmentFree(const CollisionMap& collision, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b) const {
  const double r = config_.collision_radius, cell = collision.cellSize();
  const double length = (b - a).norm();
  const Eigen::Vector3d dir = length > 0.0 ? Eigen::Vector3d((b - a) / length) : Eigen::Vector3d::Zero();
  // distance() over-estimates by at most about half a cell: step by what is left.
  for (double t = 0.0;;) {
    const double d = collision.distance(a + t * dir);
    if (!(d > r)) return false;
    if (t >= length) return true;
    t = std::min(length, t + std::max(d - r - cell, 0.5 * cell));
  }
}

std::vector<Cluster> ViewpointClusterer::cluster(const CollisionMap& collision, size_t num_ises,
                                                 std::vector<Viewpoint>* viewpoints,
                                                 std::vector<std::pair<int, int>>* links) const {
  std::vector<Viewpoint>& q = *viewpoints;
  const int n = static_cast<int>(q.size());
  AlignedBox box;
  for (const Viewpoint& v : q) box.extend(v.position);
  PointGrid grid(box, config_.d_nu_max, q.size());
  for (int i = 0; i < n; ++i) grid.insert(i, q[i].position);
  // Viewpoints within d_nu_max of i, by distance then index.
  auto around = [&](int i) {
    std::vector<std::pair<double, int>> out;
    grid.forEachNear(q[i].position, [&](int j) {
      const double d = (q[j].position - q[i].position).norm();
      if (j != i && d < config_.d_nu_max) out.emplace_back(d, j);
    });
    std::sort(out.begin(), out.end());
    return out;
  };

  // Neighbours within d_nu, each pair tested once (by its smaller index).
  std::vector<std::vector<int>> near(n);
  parallelForChunked(q.size(), config_.threads, 32, [&](size_t i) {
    for (const auto& [d, j] : around(static_cast<int>(i))) {
      if (d >= config_.d_nu) break;
      if (j > static_cast<int>(i) && segmentFree(collision, q[i].position, q[j].position)) near[i].push_back(j);
    }
  });
  std::vector<uint8_t> linked(n, 0);
  for (int i = 0; i < n; ++i) {
    for (int j : near[i]) linked[i] = linked[j] = 1;
  }
  // A viewpoint with no neighbour widens its radius by d_nu_step (up to
  // d_nu_max) until it finds one: the first radius of that sequence beyond
  // its nearest reachable viewpoint, keeping every reachable one inside it.
  std::vector<std::vector<int>> grown(n);
  parallelForChunked(q.size(), config_.threads, 32, [&](size_t i) {
    if (linked[i]) return;
    double radius = -1.0;
    for (const auto& [d, j] : around(static_cast<int>(i))) {
      if (radius >= 0.0 && d >= radius) break;
      if (!segmentFree(collision, q[i].position, q[j].position)) continue;
      if (radius < 0.0) {
        const double k = std::floor((d - config_.d_nu) / config_.d_nu_step) + 1.0;
        radius = std::min(config_.d_nu + k * config_.d_nu_step, config_.d_nu_max);
      }
      grown[i].push_back(j);
    }
  });

  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  if (links != nullptr) links->clear();
  for (int i = 0; i < n; ++i) {
    for (const std::vector<int>* list : {&near[i], &grown[i]}) {
      for (int j : *list) {
        const int a = findRoot(&parent, i), b = findRoot(&parent, j);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
        if (links != nullptr) links->emplace_back(std::min(i, j), std::max(i, j));
      }
    }
  }
  if (links != nullptr) {
    std::sort(links->begin(), links->end());
    links->erase(std::unique(links->begin(), links->end()), links->end());
  }

  std::vector<Cluster> clusters;
  std::vector<int> cluster_of_root(n, -1);
  for (int i = 0; i < n; ++i) {
    const int root = findRoot(&parent, i);
    if (cluster_of_root[root] < 0) {
      cluster_of_root[root] = static_cast<int>(clusters.size());
      clusters.emplace_back();
    }
    q[i].cluster = cluster_of_root[root];
    clusters[q[i].cluster].viewpoints.push_back(static_cast<uint32_t>(i));
  }
  // Eq. 3: the union of the C_q of each cluster.
  std::vector<uint32_t> seen(num_ises, 0);
  for (size_t c = 0; c < clusters.size(); ++c) {
    const uint32_t stamp = static_cast<uint32_t>(c + 1);
    size_t count = 0;
    for (uint32_t i : clusters[c].viewpoints) {
      for (uint32_t k : q[i].visible) {
        if (k < num_ises && seen[k] != stamp) {
          seen[k] = stamp;
          ++count;
        }
      }
    }
    clusters[c].visible_ises = count;
    clusters[c].gain = clusterGain(count, num_ises);
  }
  return clusters;
}

}  // namespace surface_nbv
