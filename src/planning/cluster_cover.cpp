#include "surface_nbv/planning/cluster_cover.h"

#include <algorithm>
#include <unordered_set>

namespace surface_nbv {

Frontier coverClusters(const Frontier& frontier, const std::vector<char>& preferred, size_t min_new,
                       ClusterCoverStats* stats) {
  Frontier f = frontier;
  ClusterCoverStats counts;
  auto priority = [&](uint32_t i) { return i < preferred.size() ? preferred[i] : 0; };
  for (size_t c = 0; c < f.clusters.size(); ++c) {
    Cluster& cluster = f.clusters[c];
    std::unordered_set<uint32_t> seen;
    std::vector<uint32_t> chosen, rest;
    auto added = [&](uint32_t i) {
      size_t n = 0;
      for (uint32_t ise : f.viewpoints[i].visible) n += seen.count(ise) == 0;
      return n;
    };
    auto take = [&](uint32_t i) {
      seen.insert(f.viewpoints[i].visible.begin(), f.viewpoints[i].visible.end());
      chosen.push_back(i);
    };
    // Preferred viewpoints first, the highest priority first.
    std::vector<uint32_t> order = cluster.viewpoints;
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return priority(a) > priority(b); });
    for (uint32_t i : order) {
      if (priority(i) > 0 && added(i) > 0) {
        take(i);
      } else {
        rest.push_back(i);
      }
    }
    std::sort(rest.begin(), rest.end());
    while (!rest.empty()) {
      size_t best = 0, best_added = added(rest[0]);
      for (size_t k = 1; k < rest.size(); ++k) {
        const size_t n = added(rest[k]);
        if (n > best_added) best = k, best_added = n;  // ties keep the lowest index (rest is ascending)
      }
      if (best_added == 0 || (best_added < min_new && !chosen.empty())) break;
      take(rest[best]);
      rest.erase(rest.begin() + static_cast<long>(best));
    }
    for (uint32_t i : rest) f.viewpoints[i].cluster = -1;
    std::sort(chosen.begin(), chosen.end());
    counts.kept += chosen.size();
    counts.dropped += rest.size();
    cluster.viewpoints = std::move(chosen);
  }
  if (stats != nullptr) *stats = counts;
  return f;
}

}  // namespace surface_nbv
