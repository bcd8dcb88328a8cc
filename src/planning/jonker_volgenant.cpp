#include "surface_nbv/planning/jonker_volgenant.h"

#include <algorithm>
#include <limits>

namespace surface_nbv {

JvTransform jonkerVolgenant(const CostMatrix& atsp, double offset) {
  const int n = atsp.size();
  double lo = std::numeric_limits<double>::max(), hi = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      lo = std::min(lo, atsp(i, j));
      hi = std::max(hi, atsp(i, j));
    }
  }
  if (n < 2) lo = 0.0;
  JvTransform jv;
  jv.atsp_nodes = n;
  jv.offset = offset >= 0 ? offset : n * (hi - lo) + 1.0;
  jv.forbidden = 2.0 * n * (hi + jv.offset) + 1.0;
  jv.symmetric = CostMatrix(2 * n, jv.forbidden);
  for (int i = 0; i < n; ++i) {
    jv.symmetric.at(i, i) = 0.0;
    jv.symmetric.at(n + i, n + i) = 0.0;
    jv.symmetric.at(i, n + i) = 0.0;
    jv.symmetric.at(n + i, i) = 0.0;
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      jv.symmetric.at(n + i, j) = atsp(i, j) + jv.offset;
      jv.symmetric.at(j, n + i) = atsp(i, j) + jv.offset;
    }
  }
  return jv;
}

std::vector<int> atspToSymmetricTour(const std::vector<int>& atsp_tour, int atsp_nodes) {
  std::vector<int> out;
  out.reserve(2 * atsp_tour.size());
  for (int i : atsp_tour) {
    out.push_back(i);
    out.push_back(atsp_nodes + i);
  }
  return out;
}

bool symmetricToAtspTour(const std::vector<int>& symmetric_tour, int atsp_nodes, std::vector<int>* atsp_tour) {
  atsp_tour->clear();
  const int m = 2 * atsp_nodes;
  if (static_cast<int>(symmetric_tour.size()) != m) return false;
  std::vector<char> seen(m, 0);
  for (int v : symmetric_tour) {
    if (v < 0 || v >= m || seen[v]) return false;
    seen[v] = 1;
  }
  if (m == 0) return true;
  // Direction: +1 if the node after an in node is its out node.
  const int first_in = symmetric_tour[0] < atsp_nodes ? 0 : 1;
  const int in0 = symmetric_tour[first_in];
  const int dir = symmetric_tour[(first_in + 1) % m] == in0 + atsp_nodes ? 1 : -1;
  for (int k = 0; k < atsp_nodes; ++k) {
    const int p = ((first_in + dir * 2 * k) % m + m) % m;
    const int in = symmetric_tour[p];
    if (in >= atsp_nodes || symmetric_tour[((p + dir) % m + m) % m] != in + atsp_nodes) {
      atsp_tour->clear();
      return false;
    }
    atsp_tour->push_back(in);
  }
  return true;
}

}  // namespace surface_nbv
