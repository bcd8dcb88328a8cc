// Collision-free paths for the UAV between two poses (x, y, z, yaw) with
// OMPL's LazyPRM* over the map bounds (docs/method.md, "Cluster graph and tour",
// "Replanning").
//
// Configuration space: R^3 positions only; the yaw is interpolated linearly
// (shortest way round) along the path by arc length. The collision body is a
// ball, so yaw never changes validity: sampling SE(2)xR would only add a
// dimension the roadmap must cover and a weight to tune in the metric, while
// the tracker turns the yaw independently of the translation.
//
// Validity: a state is valid iff CollisionMap::isFree(p, collision_radius +
// resolution / 2); motions are checked every `resolution` metres, so every
// point of an accepted edge lies within resolution / 2 of a checked state and
// is itself clear of collision_radius. Unknown space counts as an obstacle if
// the CollisionMap was built with unknown_is_obstacle (its default).
//
// The roadmap persists between plan() calls (multi-query). OMPL's LazyPRM*
// samples, connects and grows it; a query adds its start and goal as
// milestones (as LazyPRM::solve does) and is answered by our own A* over the
// roadmap graph with LazyPRM's lazy validation (the interior vertices of the
// shortest graph path are checked and every invalid one removed, then its
// edges from the goal end, the first invalid one removed, and again), on
// flat arrays without OMPL's per-removal relabelling of connected components
// (relabelled once, only before solve() reads them). Only when the graph
// holds no path does LazyPRM::solve grow the roadmap until one exists.
// Checked vertices and edges stay valid until mapChanged() marks them all
// unchecked again (it advances the epoch the flags are stamped with; only
// before OMPL itself reads them are old flags reset, in one walk over the
// graph), so the next queries re-check,
// lazily, only what their candidate paths use; what is found invalid is
// removed, and new samples repopulate freed space. Measured (bench_explorer
// BM_PathQuery, power-plant frontier, 771-vertex roadmap, 2 loaded cores):
// per-query median 0.023 ms (mean 0.25 ms) against 0.086 ms (mean 2.7 ms)
// for one LazyPRM::solve per query and 0.038 ms (1.1 ms) for OMPL's search.
// Sampling is seeded per planner, so the same calls give the same paths.
// Thread safety: none; one planner per thread. Units: metres, radians, world frame.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/common.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

class CollisionMap;

// How plan() answers from the kept roadmap (all grow it with LazyPRM::solve
// when it holds no path).
enum class QuerySearch {
  kFast,        // our lazy A* over the roadmap graph (see above)
  kOmplSearch,  // OMPL's LazyPRM::constructSolution on the same graph: the
                // reference the fast search is tested against (same paths)
  kOmplSolve,   // one LazyPRM::solve per query, as OMPL ships it: it adds a
                // sample first, then searches (the behaviour before kFast)
};

struct PathPlannerConfig {
  double collision_radius = 1.0;      // paper's UAV radius [m]
  double validity_resolution = 0.0;   // motion-check step [m]; 0 = half the collision cell
  double time_budget = 0.5;           // wall-time per plan() [s]; 0 gives kTimeout at once
  int iteration_budget = 0;           // roadmap samples per plan(); 0 = bounded by time only
  unsigned int seed = 1;              // sampler seed
  bool stop_at_first_solution = true; // false: LazyPRM* improves the path until the budget ends
  bool simplify = true;               // greedy collision-checked shortcutting of the path
  QuerySearch search = QuerySearch::kFast;  // how plan() searches the kept roadmap
  // When the roadmap's graph holds no path, an A* over a lattice of this
  // step [m] anchored at the start, checked with the same motion validity
  // (lattice_search.h), tries before the roadmap grows (with kOmplSolve,
  // after it): tight spots, narrow passages and thin free slabs that
  // sampling misses, without growing the roadmap for them. 0 = off.
  double lattice_step = 0.0;
  size_t lattice_max_nodes = 200000;  // lattice nodes expanded at most per plan()

  // Names the first bad key, e.g. "collision_radius expected > 0".
  Status validate() const;
};

enum class PathStatus {
  kExactSolution,        // a path from start to goal
  kApproximateSolution,  // not produced by LazyPRM*; kept for OMPL parity
  kTimeout,              // the time budget ended with no path
  kInvalidStart,         // start out of bounds or in collision
  kInvalidGoal,          // goal out of bounds or in collision
  kNoSolution,           // the iteration budget ended with no path
  kInvalidInput,         // no map, bad config or bounds, non-finite pose
};

const char* toString(PathStatus status);

inline bool hasPath(PathStatus status) {
  return status == PathStatus::kExactSolution || status == PathStatus::kApproximateSolution;
}

struct PathResult {
  PathStatus status = PathStatus::kInvalidInput;
  std::vector<Eigen::Vector4d> path;  // (x, y, z, yaw); empty unless hasPath(status)
  double length = 0.0;                // translational length [m]
  double seconds = 0.0;               // wall time of the call
  bool from_lattice = false;          // the lattice fallback found the path
  bool from_guide = false;            // the path follows plan()'s guide
  size_t lattice_nodes = 0;           // nodes the lattice expanded, for the guide too (0: not run)
  bool roadmap_grew = false;          // the roadmap held no path and was sampled larger
};

class PathPlanner {
 public:
  // `config` must validate(); the constructor trusts it.
  explicit PathPlanner(const PathPlannerConfig& config = PathPlannerConfig());
  ~PathPlanner();
  PathPlanner(const PathPlanner&) = delete;
  PathPlanner& operator=(const PathPlanner&) = delete;

  // The map to plan in (not owned; must outlive its use) and the sampling
  // bounds. The same bounds keep the roadmap (as mapChanged()); new bounds
  // start a new one. Error on a null map or an empty box.
  Status setMap(const CollisionMap* map, const AlignedBox& bounds);
  // The clearance every state of a path keeps from obstacles: the collision
  // radius plus half the motion-check step (set by setMap; the radius before).
  double clearance() const;
  // Call after the CollisionMap was updated: roadmap validity is re-checked lazily.
  void mapChanged();
  // Drops the roadmap; the next plan() starts from scratch with the seed.
  void clear();

  // `max_seconds` caps this call's wall time below config.time_budget (the
  // roadmap's and the lattice's together): a caller's budget for several
  // calls (ExplorerConfig::leg_time_budget). Past it the answer is kTimeout.
  // With the lattice on, the roadmap stops at half the cap and leaves the
  // lattice the rest.
  //
  // `guide` (optional): a way from near the start to near the goal, such as
  // ReachableSpace::corridor(). When the roadmap's graph holds no path it is
  // followed before the lattice and the growth: straight motions between
  // its points, the lattice (with a tenth of its node budget) across the
  // stretches the planner refuses. A far goal then costs a walk along the
  // guide instead of a lattice search over everything nearer.
  PathResult plan(const Eigen::Vector4d& start, const Eigen::Vector4d& goal,
                  double max_seconds = std::numeric_limits<double>::infinity(),
                  const std::vector<Eigen::Vector3d>* guide = nullptr);
  // Length of plan(start, goal) with yaw 0, or +infinity if it has no path.
  double pathLength(const Eigen::Vector3d& start, const Eigen::Vector3d& goal);

  // Path length between two points, +infinity when none is known; see distanceOracle().
  using DistanceOracle = std::function<double(const Eigen::Vector3d&, const Eigen::Vector3d&)>;
  // A cheap path-length oracle for one cluster graph (its cache lives as
  // long as the returned function; the planner must outlive it). The
  // straight line when that motion is collision-free, else the length of the
  // shortest roadmap path between the points' attachments (up to 6 nearby
  // roadmap vertices each, in free straight line), found by a Dijkstra per
  // source that is resumed for each new target and checks each vertex and
  // edge it settles through, sharing the checked flags with plan(); +infinity
  // when the roadmap does not connect them. Never below the straight-line
  // distance; symmetric (answers are cached per unordered pair). Adds no
  // milestone and samples nothing, so plan() results do not depend on it.
  DistanceOracle distanceOracle();

  // Roadmap vertices currently held (for tests and statistics).
  size_t roadmapVertices() const;
  // The roadmap as line segments (pairs of endpoints), at most max_edges of
  // them, for display. Edges not yet checked are included (it is lazy).
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> roadmapEdges(size_t max_edges) const;

 private:
  struct Impl;
  PathPlannerConfig config_;
  std::unique_ptr<Impl> impl_;
  // With the lattice on: the start from which the lattice and then a growth
  // found no path, and the map change count then. From that start, until
  // the map changes, the roadmap does not grow again: each such growth
  // failed as the first did and left its samples in the roadmap (a deck's
  // inside, docs/scaling.md: 69 failed growths and 130k vertices in one
  // decision).
  Eigen::Vector3d stuck_start_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  uint64_t map_changes_ = 0, stuck_at_change_ = 0;
};

}  // namespace surface_nbv
