// The roadmap of PathPlanner (path_planner.cpp only): OMPL's LazyPRM* with
// our own searches over its graph. Not a public header.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <vector>

#include <Eigen/Core>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>

#include "surface_nbv/planning/grid_neighbors.h"

namespace surface_nbv {
namespace roadmap_detail {

namespace ob = ompl::base;
namespace og = ompl::geometric;

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();

inline Eigen::Vector3d toPoint(const ob::State* state) {
  const auto* s = state->as<ob::RealVectorStateSpace::StateType>();
  return Eigen::Vector3d(s->values[0], s->values[1], s->values[2]);
}

// A roadmap vertex (dense index) reached from a point by a checked straight
// motion of `length` metres.
struct Attachment {
  uint32_t vertex = 0;
  double length = 0.0;
};

// LazyPRM* whose roadmap graph we search ourselves. OMPL samples, connects
// and grows the graph (addMilestone, solve); query() answers from the graph
// with a lazy A* when it can and lets solve() grow the graph when it cannot.
// Validity flags: OMPL's VALIDITY_TRUE (1) and our kKnownInvalid (2), which
// OMPL reads as unknown, so it re-checks and removes such an element if its
// own search meets one. The bits above them hold the map epoch of the check:
// mapChanged() only advances the epoch, and our searches treat a flag of an
// older epoch as unchecked. OMPL reads only bit 1, so before OMPL searches
// (solve(), kOmplSearch) the flags of older epochs are reset in one walk
// over the graph (what clearValidity() did after every map change).
// Vertices carry dense indices (vertex_index) for flat search arrays; they
// are renumbered after OMPL or a removal changed the graph. OMPL's connected
// components are only relabelled before OMPL reads them (solve()).
class Roadmap : public og::LazyPRMstar {
 public:
  static constexpr unsigned int kKnownInvalid = 2;
  // Query modes: our search, OMPL's search (the reference), or solve() only.
  static constexpr int kFastSearch = 0, kOmplSearch = 1, kGrowOnly = 2;

  // Neighbours come from a grid (grid_neighbors.h) instead of OMPL's GNAT:
  // the same k nearest, without GNAT's full rebuilds on removals.
  explicit Roadmap(const ob::SpaceInformationPtr& si) : og::LazyPRMstar(si) {
    const ob::RealVectorBounds& b = si->getStateSpace()->as<ob::RealVectorStateSpace>()->getBounds();
    nn_ = std::make_shared<GridNeighbors<Vertex>>([this](const Vertex& v) { return toPoint(stateProperty_[v]); },
                                                  Eigen::Vector3d(b.low[0], b.low[1], b.low[2]),
                                                  Eigen::Vector3d(b.high[0], b.high[1], b.high[2]));
  }

  // One source's Dijkstra, resumable (see distanceTo).
  struct Search {
    struct Entry {
      double d;
      uint32_t vertex, parent;  // parent kNone: reached straight from the source
      bool operator>(const Entry& o) const { return d > o.d || (d == o.d && vertex > o.vertex); }
    };
    std::vector<double> tentative;
    std::vector<char> settled;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  };

  // The problem definition's start and goal join the roadmap as milestones
  // (as solve() adds them). kFastSearch: our lazy A* over the graph, and
  // kOmplSearch: OMPL's constructSolution. A graph without a path first
  // asks `before_growing` (when given), which may answer with a path of its
  // own (true, `path` written); else, and with kGrowOnly, solve(ptc) samples
  // until the path exists and is valid. The raw roadmap path (start to
  // goal) is written to `path`.
  ob::PlannerStatus query(const ob::PlannerTerminationCondition& ptc, const std::function<bool()>& timed_out,
                          int mode, std::vector<Eigen::Vector3d>* path,
                          const std::function<bool(std::vector<Eigen::Vector3d>*)>& before_growing = {}) {
    checkValidity();
    grew_ = false;
    const ob::State* start = pis_.nextStart();
    if (start == nullptr) return ob::PlannerStatus::INVALID_START;
    const ob::State* goal = pis_.nextGoal();
    if (goal == nullptr) return ob::PlannerStatus::INVALID_GOAL;
    const Vertex s = addIndexed(si_->cloneState(start));
    startM_.push_back(s);
    const Vertex g = addIndexed(si_->cloneState(goal));
    goalM_.push_back(g);
    if (mode == kFastSearch) {
      std::vector<uint32_t> route;
      const int found = search(s, g, timed_out, &route);
      if (found < 0) return ob::PlannerStatus::TIMEOUT;
      if (found > 0) {
        path->clear();
        for (uint32_t v : route) path->push_back(pos_[v]);
        return ob::PlannerStatus::EXACT_SOLUTION;
      }
    } else if (mode == kOmplSearch) {
      relabelComponents();
      resetStaleFlags();
      ob::PathPtr solution;
      while (!solution && vertexComponentProperty_[s] == vertexComponentProperty_[g]) {
        solution = constructSolution(s, g);
      }
      index_dirty_ = true;
      if (solution) return pathPoints(*solution, path);
    }
    if (mode != kGrowOnly && before_growing && before_growing(path)) return ob::PlannerStatus::EXACT_SOLUTION;
    relabelComponents();
    resetStaleFlags();
    grew_ = true;
    const ob::PlannerStatus status = solve(ptc);
    index_dirty_ = true;
    if (status == ob::PlannerStatus::EXACT_SOLUTION) return pathPoints(*pdef_->getSolutionPath(), path);
    return status;
  }

  // Joins a path checked free (its points and the straight motions between
  // consecutive ones) to the roadmap: each point a milestone (with its k
  // nearest, lazily), consecutive ones joined by an edge known valid in this
  // epoch. Later queries find the way the path found (the lattice's,
  // through a slab few samples reach) in the graph.
  void addFreePath(const std::vector<Eigen::Vector3d>& points) {
    Vertex previous = 0;
    for (size_t k = 0; k < points.size(); ++k) {
      ob::State* state = si_->allocState();
      auto* values = state->as<ob::RealVectorStateSpace::StateType>()->values;
      for (int i = 0; i < 3; ++i) values[i] = points[k][i];
      const Vertex m = addIndexed(state);
      vertexValidityProperty_[m] = (epoch_ << kEpochShift) | VALIDITY_TRUE;
      if (k > 0) {
        auto [edge, added] = boost::add_edge(previous, m, g_);
        if (added) weightProperty_[edge] = ob::Cost((points[k] - points[k - 1]).norm());
        edgeValidityProperty_[edge] = (epoch_ << kEpochShift) | VALIDITY_TRUE;
        uniteComponents(previous, m);
      }
      previous = m;
    }
  }

  // The map changed: every validity flag checked so far is out of date.
  void mapChanged() {
    ompl_flags_stale_ = true;
    if (++epoch_ <= kMaxEpoch) return;
    epoch_ = 1;  // wrapped: no flag may look current
    for (auto [it, end] = boost::vertices(g_); it != end; ++it) vertexValidityProperty_[*it] = VALIDITY_UNKNOWN;
    for (auto [it, end] = boost::edges(g_); it != end; ++it) edgeValidityProperty_[*it] = VALIDITY_UNKNOWN;
  }

  // The last query went to solve(), which sampled the roadmap larger.
  bool grew() const { return grew_; }
  // Changes whenever vertices are added, removed or renumbered.
  uint64_t version() const { return version_; }
  const std::vector<Eigen::Vector3d>& positions() {
    renumberIfDirty();
    return pos_;
  }
  bool vertexValid(uint32_t v) { return vertexValid(byIndex_[v]); }

  // Starts a search from a point attached to the roadmap.
  void startSearch(const std::vector<Attachment>& from, Search* search) {
    search->tentative.assign(pos_.size(), kInf);
    search->settled.assign(pos_.size(), 0);
    for (const Attachment& a : from) push(search, a.length, a.vertex, kNone);
  }
  // Shortest roadmap distance from the search's source to a point attached
  // by `to`, settling vertices only as far as needed; +inf if none is
  // reached. Each vertex is settled through the edge that reaches it first,
  // checked then (vertex and edge); an invalid one is flagged kKnownInvalid,
  // not removed, so indices stay valid while searches are kept.
  double distanceTo(Search* search, const std::vector<Attachment>& to) {
    double best = kInf;
    for (const Attachment& a : to)
      if (search->settled[a.vertex]) best = std::min(best, search->tentative[a.vertex] + a.length);
    while (!search->open.empty() && search->open.top().d < best) {
      const Search::Entry e = search->open.top();
      search->open.pop();
      if (search->settled[e.vertex] || e.d > search->tentative[e.vertex]) continue;
      const Vertex v = byIndex_[e.vertex];
      if (!vertexValid(v)) continue;
      if (e.parent != kNone) {
        const auto edge = boost::edge(byIndex_[e.parent], v, g_);
        if (!edge.second || !edgeValid(edge.first, byIndex_[e.parent], v)) {
          // Other settled neighbours may still reach it: their offers were
          // dropped as worse than this one, so they are made again.
          search->tentative[e.vertex] = kInf;
          forEachNeighbour(v, [&](uint32_t u, double w) {
            if (search->settled[u]) push(search, search->tentative[u] + w, e.vertex, u);
          });
          continue;
        }
      }
      search->settled[e.vertex] = 1;
      for (const Attachment& a : to)
        if (a.vertex == e.vertex) best = std::min(best, e.d + a.length);
      forEachNeighbour(v, [&](uint32_t u, double w) {
        if (!search->settled[u]) push(search, e.d + w, u, e.vertex);
      });
    }
    return best;
  }

 private:
  void push(Search* search, double d, uint32_t v, uint32_t parent) {
    if (d >= search->tentative[v]) return;
    search->tentative[v] = d;
    search->open.push({d, v, parent});
  }

  static constexpr unsigned int kEpochShift = 2, kMaxEpoch = (~0u) >> kEpochShift;
  // The flag's validity bits if it was checked in this epoch, else 0 (unchecked).
  unsigned int current(unsigned int flags) const {
    return (flags >> kEpochShift) == epoch_ ? flags & (VALIDITY_TRUE | kKnownInvalid) : 0u;
  }
  bool knownInvalid(unsigned int flags) const { return current(flags) & kKnownInvalid; }

  template <typename F>
  void forEachNeighbour(Vertex v, F&& f) {
    for (auto [it, end] = boost::out_edges(v, g_); it != end; ++it) {
      if (knownInvalid(edgeValidityProperty_[*it])) continue;
      const Vertex u = boost::target(*it, g_);
      if (knownInvalid(vertexValidityProperty_[u])) continue;
      f(static_cast<uint32_t>(indexProperty_[u]), weightProperty_[*it].value());
    }
  }

  bool vertexValid(Vertex v) {
    unsigned int& flags = vertexValidityProperty_[v];
    if (const unsigned int known = current(flags)) return known & VALIDITY_TRUE;
    flags = (epoch_ << kEpochShift) | (si_->isValid(stateProperty_[v]) ? VALIDITY_TRUE : kKnownInvalid);
    return flags & VALIDITY_TRUE;
  }
  // The motion is checked from a to b, as constructSolution checks it.
  bool edgeValid(const Edge& e, Vertex a, Vertex b) {
    unsigned int& flags = edgeValidityProperty_[e];
    if (const unsigned int known = current(flags)) return known & VALIDITY_TRUE;
    flags = (epoch_ << kEpochShift) |
            (si_->checkMotion(stateProperty_[a], stateProperty_[b]) ? VALIDITY_TRUE : kKnownInvalid);
    return flags & VALIDITY_TRUE;
  }

  // Before OMPL reads the flags: those of older epochs become unchecked
  // (OMPL's VALIDITY_UNKNOWN in this epoch); this epoch's checks stay.
  void resetStaleFlags() {
    if (!ompl_flags_stale_) return;
    const unsigned int unknown = epoch_ << kEpochShift;
    for (auto [it, end] = boost::vertices(g_); it != end; ++it) {
      unsigned int& flags = vertexValidityProperty_[*it];
      if (!current(flags)) flags = unknown;
    }
    for (auto [it, end] = boost::edges(g_); it != end; ++it) {
      unsigned int& flags = edgeValidityProperty_[*it];
      if (!current(flags)) flags = unknown;
    }
    ompl_flags_stale_ = false;
  }

  ob::PlannerStatus pathPoints(ob::Path& solution, std::vector<Eigen::Vector3d>* path) const {
    path->clear();
    for (const ob::State* st : static_cast<og::PathGeometric&>(solution).getStates())
      path->push_back(toPoint(st));
    return ob::PlannerStatus::EXACT_SOLUTION;
  }

  Vertex addIndexed(ob::State* state) {
    renumberIfDirty();
    const Vertex m = addMilestone(state);
    indexProperty_[m] = byIndex_.size();
    byIndex_.push_back(m);
    pos_.push_back(toPoint(state));
    ++version_;
    return m;
  }

  void renumberIfDirty() {
    if (!index_dirty_) return;
    byIndex_.clear();
    pos_.clear();
    for (auto [it, end] = boost::vertices(g_); it != end; ++it) {
      indexProperty_[*it] = byIndex_.size();
      byIndex_.push_back(*it);
      pos_.push_back(toPoint(stateProperty_[*it]));
    }
    index_dirty_ = false;
    ++version_;
  }

  // OMPL's component labels, recomputed from the graph when our removals
  // left them stale: solve() only tries a path when start and goal share one.
  void relabelComponents() {
    if (!components_dirty_) return;
    renumberIfDirty();
    componentSize_.clear();
    std::vector<char> done(byIndex_.size(), 0);
    std::vector<uint32_t> stack;
    for (uint32_t root = 0; root < byIndex_.size(); ++root) {
      if (done[root]) continue;
      const unsigned long label = componentCount_++;
      done[root] = 1;
      stack.assign(1, root);
      unsigned long size = 0;
      while (!stack.empty()) {
        const Vertex v = byIndex_[stack.back()];
        stack.pop_back();
        vertexComponentProperty_[v] = label;
        ++size;
        for (auto [it, end] = boost::adjacent_vertices(v, g_); it != end; ++it) {
          const auto u = static_cast<uint32_t>(indexProperty_[*it]);
          if (!done[u]) done[u] = 1, stack.push_back(u);
        }
      }
      componentSize_[label] = size;
    }
    components_dirty_ = false;
  }

  // Lazy A*, as LazyPRM::constructSolution validates: a shortest graph path,
  // then all its unchecked interior vertices (every invalid one is removed),
  // then its edges from the goal end (the first invalid one is removed), and
  // again until a path is valid. 1 = valid path in `route` (dense indices,
  // start first), 0 = start and goal are not connected, -1 = out of time.
  //
  // Invalid vertices are removed once, when the search ends: until then A*
  // skips them (their flags say known-invalid in this epoch), which visits
  // the same vertices in the same order as removing them at once would (a
  // renumbering keeps the others' relative order), without renumbering the
  // whole roadmap after every round (on a 60 x 40 x 45 m scene's roadmap of
  // tens of thousands of vertices, that renumbering was the mission's
  // largest single cost; docs/scaling.md).
  int search(Vertex s, Vertex g, const std::function<bool()>& timed_out, std::vector<uint32_t>* route) {
    std::vector<Vertex> invalid;
    const int found = searchKeepingInvalid(s, g, timed_out, route, &invalid);
    if (invalid.empty()) return found;
    // The removal renumbers the dense indices: a found route (of valid
    // vertices only) is mapped back to vertices first, then to the new indices.
    std::vector<Vertex> path;
    if (found > 0)
      for (uint32_t v : *route) path.push_back(byIndex_[v]);
    removeVertices(invalid);
    renumberIfDirty();
    route->clear();
    for (Vertex v : path) route->push_back(static_cast<uint32_t>(indexProperty_[v]));
    return found;
  }

  int searchKeepingInvalid(Vertex s, Vertex g, const std::function<bool()>& timed_out, std::vector<uint32_t>* route,
                           std::vector<Vertex>* invalid) {
    renumberIfDirty();
    while (true) {
      if (timed_out()) return -1;
      if (!astar(static_cast<uint32_t>(indexProperty_[s]), static_cast<uint32_t>(indexProperty_[g]), route)) return 0;
      const size_t before = invalid->size();
      for (size_t k = route->size() - 1; k-- > 1;)
        if (!vertexValid(byIndex_[(*route)[k]])) invalid->push_back(byIndex_[(*route)[k]]);
      if (invalid->size() != before) continue;
      bool valid = true;
      for (size_t k = route->size() - 1; k >= 1 && valid; --k) {
        const Vertex a = byIndex_[(*route)[k - 1]], b = byIndex_[(*route)[k]];
        const Edge e = boost::edge(a, b, g_).first;
        if (!edgeValid(e, a, b)) {
          boost::remove_edge(e, g_);
          components_dirty_ = true;
          valid = false;
        }
      }
      if (valid) return 1;
    }
  }

  bool astar(uint32_t start, uint32_t goal, std::vector<uint32_t>* route) {
    const size_t n = pos_.size();
    if (cost_.size() < n) cost_.resize(n), parent_.resize(n), seen_.resize(n, 0), closed_.resize(n, 0);
    ++generation_;
    using Item = std::pair<double, uint32_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    const Eigen::Vector3d target = pos_[goal];
    seen_[start] = generation_;
    cost_[start] = 0.0;
    parent_[start] = start;
    open.push({(pos_[start] - target).norm(), start});
    while (!open.empty()) {
      const uint32_t v = open.top().second;
      open.pop();
      if (closed_[v] == generation_) continue;
      closed_[v] = generation_;
      if (v == goal) {
        route->clear();
        for (uint32_t u = goal; u != start; u = parent_[u]) route->push_back(u);
        route->push_back(start);
        std::reverse(route->begin(), route->end());
        return true;
      }
      forEachNeighbour(byIndex_[v], [&](uint32_t u, double w) {
        if (closed_[u] == generation_) return;
        const double c = cost_[v] + w;
        if (seen_[u] == generation_ && c >= cost_[u]) return;
        seen_[u] = generation_;
        cost_[u] = c;
        parent_[u] = v;
        open.push({c + (pos_[u] - target).norm(), u});
      });
    }
    return false;
  }

  // As constructSolution removes vertices: from the neighbour structure, freed, with their edges.
  void removeVertices(const std::vector<Vertex>& vertices) {
    for (Vertex v : vertices) {
      nn_->remove(v);
      si_->freeState(stateProperty_[v]);
      boost::clear_vertex(v, g_);
      boost::remove_vertex(v, g_);
    }
    index_dirty_ = components_dirty_ = true;
  }

  std::vector<Vertex> byIndex_;
  std::vector<Eigen::Vector3d> pos_;
  bool index_dirty_ = false, components_dirty_ = false;
  bool grew_ = false;
  uint64_t version_ = 0;
  unsigned int epoch_ = 1;  // of the map the validity flags are checked against
  bool ompl_flags_stale_ = false;
  std::vector<double> cost_;
  std::vector<uint32_t> parent_, seen_, closed_;
  uint32_t generation_ = 0;
};

}  // namespace roadmap_detail
}  // namespace surface_nbv
