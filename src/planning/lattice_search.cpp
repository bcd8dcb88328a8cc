#include "surface_nbv/planning/lattice_search.h"

#include <cmath>
#include <cstdint>
#include <queue>
#include <unordered_map>
#include <utility>

namespace surface_nbv {
namespace {

int64_t keyOf(const Eigen::Vector3i& c) {
  constexpr int64_t kOffset = 1 << 20;
  return ((c.x() + kOffset) << 42) | ((c.y() + kOffset) << 21) | (c.z() + kOffset);
}

struct Node {
  Eigen::Vector3i cell;
  double g = 0.0;
  int parent = -1;
  bool closed = false;
};

}  // namespace

LatticeSearchResult latticeSearch(const Eigen::Vector3d& start, const Eigen::Vector3d& goal, double step,
                                  size_t max_nodes,
                                  const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&)>& motion_free,
                                  const std::function<bool()>& should_stop) {
  LatticeSearchResult result;
  if (!(step > 0.0) || !start.allFinite() || !goal.allFinite() || max_nodes == 0) return result;
  const auto point = [&](const Eigen::Vector3i& c) -> Eigen::Vector3d { return start + step * c.cast<double>(); };
  const double reach = 2.0 * step;

  std::vector<Node> nodes;
  std::unordered_map<int64_t, int> index;
  // Open list: (f, insertion number, node); the smallest f first, then the oldest.
  using Entry = std::pair<double, std::pair<size_t, int>>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  size_t pushes = 0;
  nodes.push_back({Eigen::Vector3i::Zero(), 0.0, -1, false});
  index.emplace(keyOf(Eigen::Vector3i::Zero()), 0);
  open.push({(goal - start).norm(), {pushes++, 0}});

  std::vector<Eigen::Vector3i> offsets;
  for (int z = -1; z <= 1; ++z)
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x)
        if (x != 0 || y != 0 || z != 0) offsets.emplace_back(x, y, z);

  while (!open.empty()) {
    const int n = open.top().second.second;
    open.pop();
    if (nodes[n].closed) continue;
    nodes[n].closed = true;
    ++result.expanded;
    if (result.expanded > max_nodes || ((result.expanded & 255) == 0 && should_stop && should_stop())) {
      result.stopped = true;
      return result;
    }
    const Eigen::Vector3d p = point(nodes[n].cell);
    if ((p - goal).norm() <= reach && motion_free(p, goal)) {
      std::vector<Eigen::Vector3d> reversed{goal};
      for (int k = n; k >= 0; k = nodes[k].parent) reversed.push_back(point(nodes[k].cell));
      result.path.assign(reversed.rbegin(), reversed.rend());
      result.path.front() = start;
      result.found = true;
      return result;
    }
    for (const Eigen::Vector3i& o : offsets) {
      const Eigen::Vector3i c = nodes[n].cell + o;
      const double g = nodes[n].g + step * o.cast<double>().norm();
      const auto it = index.find(keyOf(c));
      if (it != index.end() && (nodes[it->second].closed || nodes[it->second].g <= g)) continue;
      const Eigen::Vector3d q = point(c);
      if (!motion_free(p, q)) continue;
      int m = 0;
      if (it == index.end()) {
        m = static_cast<int>(nodes.size());
        nodes.push_back({c, g, n, false});
        index.emplace(keyOf(c), m);
      } else {
        m = it->second;
        nodes[m].g = g;
        nodes[m].parent = n;
      }
      open.push({g + (q - goal).norm(), {pushes++, m}});
    }
  }
  return result;
}

}  // namespace surface_nbv
