#include "surface_nbv/planning/path_planner.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <string>
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

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace surface_nbv {

namespace {

// A uniform sampler with its own seed, so a planner's samples do not depend
// on how many OMPL random generators the process created before it.
class SeededSampler : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, unsigned int seed) : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

Eigen::Vector3d toPoint(const ob::State* state) {
  const auto* s = state->as<ob::RealVectorStateSpace::StateType>();
  return Eigen::Vector3d(s->values[0], s->values[1], s->values[2]);
}

double wrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

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
  return Status::Ok();
}

struct PathPlanner::Impl {
  const CollisionMap* map = nullptr;
  AlignedBox bounds;
  double resolution = 0.0;  // motion-check step [m]
  ob::SpaceInformationPtr si;
  std::shared_ptr<og::LazyPRMstar> prm;

  // LazyPRM's destructor does not free its roadmap states (OMPL 1.5:
  // ~LazyPRM() = default, only clear() frees them): free them here.
  ~Impl() { release(); }
  void release() {
    if (prm) prm->clear();
    prm.reset();
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
    prm = std::make_shared<og::LazyPRMstar>(si);
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
  impl_->build(config_);
  return Status::Ok();
}

void PathPlanner::mapChanged() {
  if (impl_->prm) impl_->prm->clearValidity();
}

void PathPlanner::clear() {
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

PathResult PathPlanner::plan(const Eigen::Vector4d& start, const Eigen::Vector4d& goal) {
  const auto t0 = std::chrono::steady_clock::now();
  PathResult result;
  auto finish = [&](PathStatus status) {
    result.status = status;
    if (!hasPath(status)) {
      result.path.clear();
      result.length = 0.0;
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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

  auto pdef = std::make_shared<ob::ProblemDefinition>(impl_->si);
  pdef->setStartAndGoalStates(s, g);
  auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(impl_->si);
  objective->setCostThreshold(config_.stop_at_first_solution ? ob::Cost(std::numeric_limits<double>::infinity())
                                                             : ob::Cost(0.0));
  pdef->setOptimizationObjective(objective);
  impl_->prm->setProblemDefinition(pdef);

  // Iterations are counted as evaluations of the condition: LazyPRM evaluates
  // it once per roadmap sample, so the count does not depend on timing.
  int evaluations = 0;
  const int budget = config_.iteration_budget;
  ob::PlannerTerminationCondition ptc = ob::timedPlannerTerminationCondition(config_.time_budget);
  if (budget > 0) {
    ptc = ob::plannerOrTerminationCondition(
        ptc, ob::PlannerTerminationCondition([&evaluations, budget] { return ++evaluations > budget; }));
  }
  const ob::PlannerStatus status = impl_->prm->solve(ptc);
  impl_->prm->clearQuery();

  switch (ob::PlannerStatus::StatusType(status)) {
    case ob::PlannerStatus::EXACT_SOLUTION: break;
    case ob::PlannerStatus::INVALID_START: return finish(PathStatus::kInvalidStart);
    case ob::PlannerStatus::INVALID_GOAL: return finish(PathStatus::kInvalidGoal);
    case ob::PlannerStatus::TIMEOUT:
      return finish(budget > 0 && evaluations > budget ? PathStatus::kNoSolution : PathStatus::kTimeout);
    default: return finish(PathStatus::kNoSolution);
  }
  auto* solution = pdef->getSolutionPath()->as<og::PathGeometric>();
  const std::vector<ob::State*>& states = solution->getStates();
  if (states.size() < 2) return finish(PathStatus::kNoSolution);

  // Greedy shortcutting: from each kept state jump to the farthest later
  // state reachable by a collision-free straight motion.
  std::vector<size_t> kept{0};
  const size_t n = states.size();
  while (kept.back() + 1 < n) {
    const size_t i = kept.back();
    size_t j = n - 1;
    if (config_.simplify) {
      while (j > i + 1 && !impl_->si->checkMotion(states[i], states[j])) --j;
    } else {
      j = i + 1;
    }
    kept.push_back(j);
  }
  std::vector<Eigen::Vector3d> points;
  for (size_t k : kept) points.push_back(toPoint(states[k]));
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
  return hasPath(r.status) ? r.length : std::numeric_limits<double>::infinity();
}

}  // namespace surface_nbv
