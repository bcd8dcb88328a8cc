#include "surface_nbv/planning/path_planner.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <queue>
#include <string>
#include <unordered_map>
#include <utility>

#include <ompl/base/Planner.h>
#include <ompl/base/PlannerData.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/planning/lattice_search.h"
#include "surface_nbv/util/angles.h"
#include "surface_nbv/util/bits_hash.h"
#include "lazy_roadmap.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace surface_nbv {

using roadmap_detail::Attachment;
using roadmap_detail::kInf;
using roadmap_detail::Roadmap;
using roadmap_detail::toPoint;

namespace {

// A uniform sampler with its own seed, so a planner's samples do not depend
// on how many OMPL random generators the process created before it.
class SeededSampler : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, unsigned int seed) : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

void setPoint(ob::State* state, const Eigen::Vector3d& p) {
  auto* s = state->as<ob::RealVectorStateSpace::StateType>();
  for (int i = 0; i < 3; ++i) s->values[i] = p[i];
}

// The exact bits of a point, so caches keyed by position never merge two points.
struct PointKey : BitsKey<3> {
  explicit PointKey(const Eigen::Vector3d& p) : BitsKey<3>(p.data()) {}
};
using PointKeyHash = BitsKeyHash<3>;
struct PairKeyHash {
  size_t operator()(const std::pair<PointKey, PointKey>& k) const {
    return PointKeyHash()(k.first) * 31 + PointKeyHash()(k.second);
  }
};

// The path-length oracle's memory for one cluster graph: the roadmap
// vertices by grid cell, each point's attachments, one resumable search
// per source and every answer (keyed by the ordered pair, so symmetric).
struct DistanceCache {
  const Roadmap* roadmap = nullptr;
  uint64_t version = 0;
  double cell = 1.0;
  std::unordered_map<int64_t, std::vector<uint32_t>> grid;
  std::unordered_map<PointKey, std::vector<Attachment>, PointKeyHash> attachments;
  std::unordered_map<PointKey, std::unique_ptr<Roadmap::Search>, PointKeyHash> searches;
  std::unordered_map<std::pair<PointKey, PointKey>, double, PairKeyHash> known;
};

constexpr size_t kAttach = 6;         // roadmap vertices a point is attached to
constexpr double kVerticesPerCell = 4.0;

}  // namespace

const char* toString(PathStatus status) {
  switch (status) {
    case PathStatus::kExactSolution: return "exact solution";
    case PathStatus::kApproximateSolution: return "approximate solution";
    case PathStatus::kTimeout: return "timeout";
    case PathStatus::kInvalidStart: return "invalid start";
    case PathStatus::kInvalidGoal: return "invalid goal";
    case PathStatus::kNoSolution: return "no solution";
    case PathStatus::kInvalidInput: return "invalid input";
  }
  return "unknown";
}

Status PathPlannerConfig::validate() const {
  if (!(collision_radius > 0.0) || !std::isfinite(collision_radius)) return Status::Error("collision_radius expected > 0");
  if (!(validity_resolution >= 0.0) || !std::isfinite(validity_resolution))
    return Status::Error("validity_resolution expected >= 0");
  if (!(time_budget >= 0.0) || !std::isfinite(time_budget)) return Status::Error("time_budget expected >= 0");
  if (iteration_budget < 0) return Status::Error("iteration_budget expected >= 0");
  if (!(lattice_step >= 0.0) || !std::isfinite(lattice_step)) return Status::Error("lattice_step expected >= 0");
  if (lattice_step > 0.0 && lattice_max_nodes == 0) return Status::Error("lattice_max_nodes expected >= 1");
  return Status::Ok();
}

struct PathPlanner::Impl {
  const CollisionMap* map = nullptr;
  AlignedBox bounds;
  double resolution = 0.0;  // motion-check step [m]
  ob::SpaceInformationPtr si;
  std::shared_ptr<Roadmap> prm;
  ob::OptimizationObjectivePtr objective;
  ob::State* from = nullptr;  // scratch states for motionFree
  ob::State* to = nullptr;

  // LazyPRM's destructor does not free its roadmap states (OMPL 1.5:
  // ~LazyPRM() = default, only clear() frees them): free them here.
  ~Impl() { release(); }
  void release() {
    if (prm) prm->clear();
    prm.reset();
    if (si && from) si->freeState(from), si->freeState(to);
    from = to = nullptr;
  }

  void build(const PathPlannerConfig& config) {
    release();
    auto space = std::make_shared<ob::RealVectorStateSpace>(3);
    ob::RealVectorBounds b(3);
    for (int i = 0; i < 3; ++i) {
      b.setLow(i, bounds.min[i]);
      b.setHigh(i, bounds.max[i]);
    }
    space->setBounds(b);
    const unsigned int seed = config.seed;
    space->setStateSamplerAllocator(
        [seed](const ob::StateSpace* s) { return std::make_shared<SeededSampler>(s, seed); });
    si = std::make_shared<ob::SpaceInformation>(space);
    const CollisionMap* m = map;
    const double radius = config.collision_radius + 0.5 * resolution;
    si->setStateValidityChecker([m, radius, space](const ob::State* s) {
      return space->satisfiesBounds(s) && m->isFree(toPoint(s), radius);
    });
    si->setStateValidityCheckingResolution(resolution / space->getMaximumExtent());
    si->setup();
    prm = std::make_shared<Roadmap>(si);
    objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
    objective->setCostThreshold(config.stop_at_first_solution ? ob::Cost(kInf) : ob::Cost(0.0));
    from = si->allocState();
    to = si->allocState();
  }

  // The straight motion a -> b is collision-free (b and the points between).
  bool motionFree(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    setPoint(from, a);
    setPoint(to, b);
    return si->checkMotion(from, to);
  }

  // motionFree as the lattice takes it.
  std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&)> motionCheck() {
    return [this](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return motionFree(a, b); };
  }

  bool pointFree(const Eigen::Vector3d& p) {
    setPoint(from, p);
    return si->isValid(from);
  }

  // A path start -> goal along `guide` (PathPlanner::plan): from each point
  // reached, the farthest of the next kGuideWindow guide points (the goal
  // last) in free straight motion; where none is, the lattice from there to
  // the next guide point the planner accepts, with `repair_nodes` nodes.
  // False when a repair fails, the lattice is off or should_stop says so.
  static constexpr size_t kGuideWindow = 48;
  bool followGuide(const Eigen::Vector3d& start, const Eigen::Vector3d& goal, const std::vector<Eigen::Vector3d>& guide,
                   double lattice_step, size_t repair_nodes, const std::function<bool()>& should_stop,
                   std::vector<Eigen::Vector3d>* path, size_t* expanded) {
    std::vector<Eigen::Vector3d> points = guide;
    points.push_back(goal);
    const size_t n = points.size();
    path->assign(1, start);
    Eigen::Vector3d at = start;
    size_t next = 0;  // the first guide point not yet passed
    while (next < n) {
      if (should_stop()) return false;
      bool moved = false;
      for (size_t k = std::min(next + kGuideWindow, n); k-- > next;) {
        if (motionFree(at, points[k])) {
          at = points[k];
          path->push_back(at);
          next = k + 1;
          moved = true;
          break;
        }
      }
      if (moved) continue;
      if (!(lattice_step > 0.0)) return false;
      size_t j = next;
      while (j < n && !pointFree(points[j])) ++j;
      if (j == n) return false;
      const LatticeSearchResult r = latticeSearch(at, points[j], lattice_step, repair_nodes, motionCheck(), should_stop);
      *expanded += r.expanded;
      if (!r.found) return false;
      path->insert(path->end(), r.path.begin() + 1, r.path.end());
      at = points[j];
      next = j + 1;
    }
    return true;
  }

  static int64_t cellKey(const Eigen::Vector3i& i) {
    constexpr int64_t kOffset = 1 << 20;
    return ((i.x() + kOffset) << 42) | ((i.y() + kOffset) << 21) | (i.z() + kOffset);
  }
  Eigen::Vector3i cellOf(const DistanceCache& c, const Eigen::Vector3d& p) const {
    return ((p - bounds.min) / c.cell).array().floor().cast<int>().cwiseMax(-1).cwiseMin(1 << 19);
  }

  void resetCache(DistanceCache* c) {
    *c = DistanceCache();
    c->roadmap = prm.get();
    const std::vector<Eigen::Vector3d>& pos = prm->positions();
    c->version = prm->version();
    const double volume = (bounds.max - bounds.min).prod();
    c->cell = std::cbrt(kVerticesPerCell * volume / std::max<double>(1.0, pos.size()));
    for (uint32_t v = 0; v < pos.size(); ++v) c->grid[cellKey(cellOf(*c, pos[v]))].push_back(v);
  }

  // The nearest roadmap vertices (up to kAttach) valid and in free straight
  // line from p, searched in the 3^3 and then 5^3 cells around p.
  const std::vector<Attachment>& attachments(DistanceCache* c, const Eigen::Vector3d& p) {
    auto [it, fresh] = c->attachments.try_emplace(PointKey(p));
    if (!fresh) return it->second;
    const std::vector<Eigen::Vector3d>& pos = prm->positions();
    const Eigen::Vector3i centre = cellOf(*c, p);
    std::vector<std::pair<double, uint32_t>> candidates;
    for (int r = 1; r <= 2 && candidates.size() < 2 * kAttach; ++r) {
      candidates.clear();
      for (int x = -r; x <= r; ++x)
        for (int y = -r; y <= r; ++y)
          for (int z = -r; z <= r; ++z) {
            const auto cell = c->grid.find(cellKey(centre + Eigen::Vector3i(x, y, z)));
            if (cell == c->grid.end()) continue;
            for (uint32_t v : cell->second) candidates.emplace_back((pos[v] - p).norm(), v);
          }
    }
    std::sort(candidates.begin(), candidates.end());
    for (size_t k = 0; k < candidates.size() && k < 4 * kAttach && it->second.size() < kAttach; ++k) {
      const uint32_t v = candidates[k].second;
      if (prm->vertexValid(v) && motionFree(p, pos[v])) it->second.push_back({v, candidates[k].first});
    }
    return it->second;
  }

  double distance(DistanceCache* c, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    if (!prm) return (a - b).norm();
    const bool swap = PointKey(b) < PointKey(a);
    const Eigen::Vector3d& x = swap ? b : a;
    const Eigen::Vector3d& y = swap ? a : b;
    const PointKey kx(x), ky(y);
    if (kx == ky) return 0.0;
    if (c->roadmap != prm.get() || c->version != prm->version()) resetCache(c);
    const auto known = c->known.find({kx, ky});
    if (known != c->known.end()) return known->second;
    double d = (x - y).norm();
    if (!motionFree(x, y)) {
      const std::vector<Attachment>& targets = attachments(c, y);
      std::unique_ptr<Roadmap::Search>& search = c->searches[kx];
      if (!search) {
        search = std::make_unique<Roadmap::Search>();
        prm->startSearch(attachments(c, x), search.get());
      }
      d = prm->distanceTo(search.get(), targets);
    }
    c->known.emplace(std::make_pair(kx, ky), d);
    return d;
  }
};

PathPlanner::PathPlanner(const PathPlannerConfig& config) : config_(config), impl_(std::make_unique<Impl>()) {}

PathPlanner::~PathPlanner() = default;

Status PathPlanner::setMap(const CollisionMap* map, const AlignedBox& bounds) {
  if (map == nullptr) return Status::Error("map expected non-null");
  if (bounds.empty() || !bounds.min.allFinite() || !bounds.max.allFinite() ||
      !((bounds.max - bounds.min).array() > 0.0).all())
    return Status::Error("bounds expected a non-empty finite box");
  const double resolution =
      config_.validity_resolution > 0.0 ? config_.validity_resolution : 0.5 * map->cellSize();
  if (impl_->prm && impl_->map == map && impl_->bounds.min == bounds.min && impl_->bounds.max == bounds.max &&
      impl_->resolution == resolution) {
    mapChanged();
    return Status::Ok();
  }
  impl_->map = map;
  impl_->bounds = bounds;
  impl_->resolution = resolution;
  ++map_changes_;
  impl_->build(config_);
  return Status::Ok();
}

void PathPlanner::mapChanged() {
  ++map_changes_;
  if (impl_->prm) impl_->prm->mapChanged();
}

void PathPlanner::clear() {
  ++map_changes_;  // a new roadmap: no start is stuck on it
  if (impl_->map) impl_->build(config_);
}

size_t PathPlanner::roadmapVertices() const { return impl_->prm ? impl_->prm->milestoneCount() : 0; }

std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> PathPlanner::roadmapEdges(size_t max_edges) const {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> edges;
  if (!impl_->prm) return edges;
  ob::PlannerData data(impl_->si);
  impl_->prm->getPlannerData(data);
  std::vector<unsigned int> out;
  for (unsigned int i = 0; i < data.numVertices() && edges.size() < max_edges; ++i) {
    data.getEdges(i, out);
    for (unsigned int j : out) {
      if (j <= i || edges.size() >= max_edges) continue;  // each undirected edge once
      edges.emplace_back(toPoint(data.getVertex(i).getState()), toPoint(data.getVertex(j).getState()));
    }
  }
  return edges;
}

double PathPlanner::clearance() const { return config_.collision_radius + 0.5 * impl_->resolution; }

PathResult PathPlanner::plan(const Eigen::Vector4d& start, const Eigen::Vector4d& goal, double max_seconds,
                             const std::vector<Eigen::Vector3d>* guide) {
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [t0] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  PathResult result;
  auto finish = [&](PathStatus status) {
    result.status = status;
    if (!hasPath(status)) {
      result.path.clear();
      result.length = 0.0;
    }
    result.seconds = elapsed();
    return result;
  };
  if (!impl_->prm || !start.allFinite() || !goal.allFinite() || !config_.validate()) {
    return finish(PathStatus::kInvalidInput);
  }
  ob::ScopedState<> s(impl_->si), g(impl_->si);
  for (int i = 0; i < 3; ++i) {
    s[i] = start[i];
    g[i] = goal[i];
  }
  if (!impl_->si->isValid(s.get())) return finish(PathStatus::kInvalidStart);
  if (!impl_->si->isValid(g.get())) return finish(PathStatus::kInvalidGoal);
  // The caller's cap covers the roadmap and the lattice together; the
  // config's budget applies to each of them.
  const double cap = std::isnan(max_seconds) ? 0.0 : max_seconds;
  if (config_.time_budget <= 0.0 || cap <= 0.0) return finish(PathStatus::kTimeout);
  const double budget_s = std::min(config_.time_budget, cap);
  // With the lattice on, a caller's cap (the ROS planner's leg_time_budget)
  // is shared: the lattice, asked before the roadmap grows, stops at half of
  // it, so that the growth, which finds long ways round, still has time
  // when the lattice has none to spare. Without a cap nothing changes.
  const double roadmap_s = budget_s;
  const double lattice_cap = config_.lattice_step > 0.0 && std::isfinite(cap) ? 0.5 * cap : cap;

  auto pdef = std::make_shared<ob::ProblemDefinition>(impl_->si);
  pdef->setStartAndGoalStates(s, g);
  pdef->setOptimizationObjective(impl_->objective);
  impl_->prm->setProblemDefinition(pdef);

  // Iterations are counted as evaluations of the condition: LazyPRM evaluates
  // it once per roadmap sample, so the count does not depend on timing.
  int evaluations = 0;
  const int budget = config_.iteration_budget;
  ob::PlannerTerminationCondition ptc = ob::timedPlannerTerminationCondition(roadmap_s);
  if (budget > 0) {
    ptc = ob::plannerOrTerminationCondition(
        ptc, ob::PlannerTerminationCondition([&evaluations, budget] { return ++evaluations > budget; }));
  }
  // Improving a path until the budget ends is solve()'s job; a graph search
  // stops at the first (shortest) roadmap path.
  const int mode = !config_.stop_at_first_solution || config_.search == QuerySearch::kOmplSolve ? Roadmap::kGrowOnly
                   : config_.search == QuerySearch::kFast                                        ? Roadmap::kFastSearch
                                                                                                  : Roadmap::kOmplSearch;
  // With the lattice on, a graph without a path asks the lattice before the
  // roadmap grows. Growing samples the whole bounds by up to
  // iteration_budget milestones, and where the free space is a thin slab
  // (a deck's 3 m under a ceiling, less the clearance twice) few samples
  // land in it and the k nearest of those that do lie across the floors:
  // the growth fails and the roadmap keeps thousands of vertices for each
  // such query (docs/scaling.md). The lattice has its own node budget (and
  // the wall-time budget again as a safety net).
  bool lattice_tried = false;
  double lattice_until = lattice_cap;  // before the growth; after it (kGrowOnly), the whole cap
  bool guide_tried = false;
  // Asked when the graph holds no path: the guide first, then the lattice.
  const auto fallback = [&](std::vector<Eigen::Vector3d>* path) {
    if (guide != nullptr && !guide->empty() && !guide_tried) {
      guide_tried = true;
      const double deadline = std::min(elapsed() + budget_s, lattice_until);
      if (impl_->followGuide(start.head<3>(), goal.head<3>(), *guide, config_.lattice_step,
                             std::max<size_t>(config_.lattice_max_nodes / 10, 1), [&elapsed, deadline] {
                               return elapsed() > deadline;
                             }, path, &result.lattice_nodes)) {
        result.from_guide = true;
        return true;
      }
    }
    if (!(config_.lattice_step > 0.0)) return false;
    lattice_tried = true;
    const double deadline = std::min(elapsed() + budget_s, lattice_until);
    if (elapsed() >= deadline) return false;
    const LatticeSearchResult found = latticeSearch(
        start.head<3>(), goal.head<3>(), config_.lattice_step, config_.lattice_max_nodes, impl_->motionCheck(),
        [&elapsed, deadline] { return elapsed() > deadline; });
    result.lattice_nodes += found.expanded;
    if (!found.found) {
      // No growth from a start where one failed after the lattice, until the map changes.
      if (stuck_at_change_ == map_changes_ && start.head<3>() == stuck_start_) {
        path->clear();  // "answered" with no path: plan() reports kNoSolution
        return true;
      }
      return false;
    }
    *path = found.path;
    result.from_lattice = true;
    return true;
  };
  std::vector<Eigen::Vector3d> raw;
  const ob::PlannerStatus status =
      impl_->prm->query(ptc, [&elapsed, roadmap_s] { return elapsed() > roadmap_s; }, mode, &raw, fallback);
  impl_->prm->clearQuery();
  result.roadmap_grew = impl_->prm->grew();
  if (result.roadmap_grew && lattice_tried && !result.from_lattice && !result.from_guide &&
      ob::PlannerStatus::StatusType(status) != ob::PlannerStatus::EXACT_SOLUTION) {
    stuck_start_ = start.head<3>();
    stuck_at_change_ = map_changes_;
  }

  PathStatus failure = PathStatus::kExactSolution;
  switch (ob::PlannerStatus::StatusType(status)) {
    case ob::PlannerStatus::EXACT_SOLUTION:
      if (raw.size() < 2) failure = PathStatus::kNoSolution;
      break;
    case ob::PlannerStatus::INVALID_START: return finish(PathStatus::kInvalidStart);
    case ob::PlannerStatus::INVALID_GOAL: return finish(PathStatus::kInvalidGoal);
    case ob::PlannerStatus::TIMEOUT:
      failure = budget > 0 && evaluations > budget ? PathStatus::kNoSolution : PathStatus::kTimeout;
      break;
    default: failure = PathStatus::kNoSolution;
  }
  // The modes that only grow (kGrowOnly) ask the lattice after the growth.
  lattice_until = cap;
  if (failure != PathStatus::kExactSolution && (lattice_tried || !fallback(&raw))) return finish(failure);

  // Greedy shortcutting: from each kept point jump to the farthest later
  // point reachable by a collision-free straight motion.
  std::vector<size_t> kept{0};
  const size_t n = raw.size();
  while (kept.back() + 1 < n) {
    const size_t i = kept.back();
    size_t j = n - 1;
    if (config_.simplify) {
      while (j > i + 1 && !impl_->motionFree(raw[i], raw[j])) --j;
    } else {
      j = i + 1;
    }
    kept.push_back(j);
  }
  std::vector<Eigen::Vector3d> points;  // without repeats (a query point may already be a milestone)
  for (size_t k : kept)
    if (points.empty() || raw[k] != points.back()) points.push_back(raw[k]);
  if (points.size() == 1) points.push_back(raw.back());
  if (result.from_lattice || result.from_guide) impl_->prm->addFreePath(points);
  std::vector<double> arc(points.size(), 0.0);
  for (size_t k = 1; k < points.size(); ++k) arc[k] = arc[k - 1] + (points[k] - points[k - 1]).norm();
  result.length = arc.back();
  const double turn = wrapAngle(goal[3] - start[3]);
  for (size_t k = 0; k < points.size(); ++k) {
    const double f = result.length > 0.0 ? arc[k] / result.length : 1.0;
    result.path.emplace_back(points[k].x(), points[k].y(), points[k].z(), wrapAngle(start[3] + f * turn));
  }
  return finish(PathStatus::kExactSolution);
}

double PathPlanner::pathLength(const Eigen::Vector3d& start, const Eigen::Vector3d& goal) {
  Eigen::Vector4d s, g;
  s << start, 0.0;
  g << goal, 0.0;
  const PathResult r = plan(s, g);
  return hasPath(r.status) ? r.length : kInf;
}

PathPlanner::DistanceOracle PathPlanner::distanceOracle() {
  auto cache = std::make_shared<DistanceCache>();
  Impl* impl = impl_.get();
  return [impl, cache](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return impl->distance(cache.get(), a, b); };
}

}  // namespace surface_nbv
