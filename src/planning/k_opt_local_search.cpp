#include "surface_nbv/planning/k_opt_local_search.h"

#include <algorithm>
#include <utility>

namespace surface_nbv {
namespace {

constexpr double kEps = 1e-9;

}  // namespace

KOptLocalSearch::KOptLocalSearch(const CostMatrix& costs, std::vector<std::vector<int>> candidates,
                                 std::vector<int> fixed_partner, int max_depth, int or_opt_max_segment,
                                 std::vector<int> breadth)
    : costs_(costs),
      candidates_(std::move(candidates)),
      fixed_(std::move(fixed_partner)),
      breadth_(std::move(breadth)),
      max_depth_(std::clamp(max_depth, 2, kMaxK)),
      or_opt_max_segment_(or_opt_max_segment),
      n_(costs.size()),
      pos_(n_),
      buffer_(n_),
      active_(n_, 0) {
  breadth_.resize(kMaxK, breadth_.empty() ? 5 : breadth_.back());
  all_fixed_ = n_ > 0 && std::all_of(fixed_.begin(), fixed_.end(), [](int p) { return p >= 0; });
}

void KOptLocalSearch::setTour(const std::vector<int>& tour) {
  tour_ = tour;
  for (int i = 0; i < n_; ++i) pos_[tour_[i]] = i;
  cost_ = costs_.tourCost(tour_);
}

void KOptLocalSearch::activate(int a) {
  if (active_[a]) return;
  active_[a] = 1;
  queue_.push_back(a);
}

void KOptLocalSearch::activateAll() {
  for (int a : tour_) activate(a);
}

bool KOptLocalSearch::optimize(Clock::time_point deadline) {
  int since_check = 0;
  while (queue_head_ < queue_.size()) {
    if (++since_check == 64) {
      since_check = 0;
      if (Clock::now() > deadline) return false;
    }
    const int t1 = queue_[queue_head_++];
    active_[t1] = 0;
    if (queue_head_ > 4096 && queue_head_ * 2 > queue_.size()) {
      queue_.erase(queue_.begin(), queue_.begin() + queue_head_);
      queue_head_ = 0;
    }
    if (improveFrom(t1) || orOptFrom(t1)) activate(t1);  // it may improve again
  }
  return true;
}

bool KOptLocalSearch::improveFrom(int t1) {
  if (n_ < 5) return false;
  for (int side = 0; side < 2; ++side) {
    const int t2 = side == 0 ? succ(t1) : pred(t1);
    if (fixedEdge(t1, t2)) continue;
    t_[0] = t1;
    t_[1] = t2;
    if (searchLevel(1, c(t1, t2))) return true;
  }
  return false;
}

// True if {a, b} is one of the first `pairs` removed (or added) edges of the move in t_.
bool KOptLocalSearch::edgeInMove(int a, int b, int pairs, bool removed) const {
  for (int i = 0; i < pairs; ++i) {
    const int x = t_[2 * i + (removed ? 0 : 1)];
    const int y = t_[2 * i + (removed ? 1 : 2)];
    if ((x == a && y == b) || (x == b && y == a)) return true;
  }
  return false;
}

// t_[0 .. 2 level - 1] hold `level` removed edges; gain = their cost minus the
// level - 1 edges added so far. Chooses edge level + 1 and tries to close.
bool KOptLocalSearch::searchLevel(int level, double gain) {
  const int t2 = t_[2 * level - 1];
  int tried = 0;
  for (int t3 : candidates_[t2]) {
    const double g1 = gain - c(t2, t3);
    if (g1 <= kEps) continue;
    if (t3 == succ(t2) || t3 == pred(t2) || edgeInMove(t2, t3, level - 1, false)) continue;
    if (++tried > breadth_[level - 1]) break;
    for (int side = 0; side < 2; ++side) {
      const int t4 = side == 0 ? succ(t3) : pred(t3);
      if (fixedEdge(t3, t4) || edgeInMove(t3, t4, level, true)) continue;
      t_[2 * level] = t3;
      t_[2 * level + 1] = t4;
      const double g2 = g1 + c(t3, t4);
      const int k = level + 1;
      const double closed = g2 - c(t4, t_[0]);
      // With every node paired (the Jonker-Volgenant form) a valid move keeps
      // each segment's direction, and such a sequential move has an odd k.
      if (closed > kEps && t4 != t_[0] && !(all_fixed_ && k % 2 == 0)) {
        int added[2 * kMaxK];
        for (int i = 0; i < 2 * k; ++i) added[i] = t_[(i + 1) % (2 * k)];
        if (applyMove(t_, added, k, closed)) return true;
      }
      if (k < max_depth_ && searchLevel(k, g2)) return true;
    }
  }
  return false;
}

bool KOptLocalSearch::orOptFrom(int t1) {
  if (n_ < 5) return false;
  const int s1 = succ(t1);
  if (fixedEdge(t1, s1)) return false;
  int s_last = s1;
  for (int len = 1; len <= or_opt_max_segment_ && len + 2 < n_; ++len) {
    if (len > 1) s_last = succ(s_last);
    const int next = succ(s_last);
    if (fixedEdge(s_last, next)) continue;
    const double removed_gain = c(t1, s1) + c(s_last, next) - c(t1, next);
    if (removed_gain <= kEps) continue;
    // Insert the segment next to a candidate of one of its ends.
    for (int end = 0; end < 2; ++end) {
      const int e = end == 0 ? s1 : s_last, other = end == 0 ? s_last : s1;
      for (int a : candidates_[e]) {
        if (c(e, a) >= removed_gain) continue;
        if ((pos_[a] - pos_[s1] + n_) % n_ < len) continue;  // inside the segment
        for (int side = 0; side < 2; ++side) {
          const int b = side == 0 ? succ(a) : pred(a);
          if ((pos_[b] - pos_[s1] + n_) % n_ < len || fixedEdge(a, b)) continue;
          if ((a == t1 && b == next) || (a == next && b == t1)) continue;
          const double gain = removed_gain + c(a, b) - c(e, a) - c(other, b);
          if (gain <= kEps) continue;
          const int removed[6] = {t1, s1, s_last, next, a, b};
          const int added[6] = {t1, next, e, a, other, b};
          if (applyMove(removed, added, 3, gain)) return true;
        }
      }
    }
  }
  return false;
}

bool KOptLocalSearch::applyMove(const int* removed, const int* added, int k, double gain) {
  // Cut r (after sorting) is the tour edge between positions cut[r] and cut[r] + 1,
  // segment r runs from cut[r - 1] + 1 to cut[r]. Endpoint 2r = start of
  // segment r, 2r + 1 = its end.
  int cut[kMaxK], order[kMaxK];
  for (int i = 0; i < k; ++i) {
    const int a = removed[2 * i], b = removed[2 * i + 1];
    cut[i] = succ(a) == b ? pos_[a] : pos_[b];
    order[i] = i;
  }
  for (int i = 1; i < k; ++i) {  // insertion sort, k is small
    for (int j = i; j > 0 && cut[order[j]] < cut[order[j - 1]]; --j) std::swap(order[j], order[j - 1]);
  }
  int sorted[kMaxK];
  for (int r = 0; r < k; ++r) sorted[r] = cut[order[r]];
  for (int r = 1; r < k; ++r) {
    if (sorted[r] == sorted[r - 1]) return false;
  }
  // Endpoint instances of the removed edges' nodes.
  int node_of[2 * kMaxK], used[2 * kMaxK] = {0};
  for (int r = 0; r < k; ++r) {
    node_of[2 * r + 1] = tour_[sorted[r]];
    node_of[2 * ((r + 1) % k)] = tour_[sorted[r] + 1 == n_ ? 0 : sorted[r] + 1];
  }
  auto endpoint = [&](int node) {
    for (int e = 0; e < 2 * k; ++e) {
      if (node_of[e] == node && !used[e]) {
        used[e] = 1;
        return e;
      }
    }
    return -1;
  };
  int mate[2 * kMaxK];
  for (int i = 0; i < k; ++i) {
    const int x = endpoint(added[2 * i]), y = endpoint(added[2 * i + 1]);
    if (x < 0 || y < 0) return false;
    mate[x] = y;
    mate[y] = x;
  }
  // Walk: enter a segment at one end, leave at the other, follow the new edge.
  int visited = 0;
  for (int e = 0;;) {
    ++visited;
    const int next = mate[e ^ 1];
    if (next == 0 || visited > k) break;
    e = next;
  }
  if (visited != k) return false;
  int w = 0;
  for (int e = 0, count = 0; count < k; ++count) {
    const int seg = e / 2;
    const int first = sorted[(seg + k - 1) % k] + 1 == n_ ? 0 : sorted[(seg + k - 1) % k] + 1;
    const int last = sorted[seg];
    const int len = (last - first + n_) % n_ + 1;
    if (e % 2 == 0) {
      for (int i = 0, p = first; i < len; ++i, p = p + 1 == n_ ? 0 : p + 1) buffer_[w++] = tour_[p];
    } else {
      for (int i = 0, p = last; i < len; ++i, p = p == 0 ? n_ - 1 : p - 1) buffer_[w++] = tour_[p];
    }
    e = mate[e ^ 1];
  }
  tour_.swap(buffer_);
  for (int i = 0; i < n_; ++i) pos_[tour_[i]] = i;
  cost_ -= gain;
  for (int i = 0; i < 2 * k; ++i) activate(removed[i]);
  return true;
}

bool KOptLocalSearch::kick(std::mt19937_64* rng, int max_segment) {
  if (n_ < 8) return false;
  const int span = std::max(1, std::min(max_segment, (n_ - 2) / 3));
  for (int attempt = 0; attempt < 20; ++attempt) {
    int q[4];
    q[0] = static_cast<int>((*rng)() % n_);
    bool ok = true;
    for (int i = 1; i < 4 && ok; ++i) q[i] = q[i - 1] + 1 + static_cast<int>((*rng)() % span);
    for (int i = 0; i < 4; ++i) {
      if (fixedEdge(tour_[q[i] % n_], tour_[(q[i] + 1) % n_])) ++q[i];
      if (i > 0 && q[i] <= q[i - 1]) ok = false;
    }
    if (!ok || q[3] - q[0] >= n_) continue;
    int a[8];
    for (int i = 0; i < 4; ++i) {
      a[2 * i] = tour_[q[i] % n_];
      a[2 * i + 1] = tour_[(q[i] + 1) % n_];
    }
    // Segments X = a1..a2, Y = a3..a4, Z = a5..a6, W = a7..a0 become X W Z Y:
    // all four edges change and no segment is reversed (valid for the JV form).
    const int added[8] = {a[2], a[7], a[0], a[5], a[6], a[3], a[4], a[1]};
    const double gain = c(a[0], a[1]) + c(a[2], a[3]) + c(a[4], a[5]) + c(a[6], a[7]) -
                        (c(a[2], a[7]) + c(a[0], a[5]) + c(a[6], a[3]) + c(a[4], a[1]));
    if (applyMove(a, added, 4, gain)) return true;
  }
  return false;
}

}  // namespace surface_nbv
