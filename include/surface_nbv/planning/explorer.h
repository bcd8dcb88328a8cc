// The replanning loop of the paper's Fig. 1 (docs/method.md, "Replanning"), ROS-free:
// given each new Frontier and the UAV's configuration, it keeps a tour of
// viewpoints and hands out the next leg to fly.
//
//   full recomputation   the cluster graph (eq. 4, 5) over the frontier and
//                        the Lin-Kernighan open path from the UAV (planTour),
//                        when there is no tour yet or every tour viewpoint
//                        has been visited,
//   local update         on every other frontier: tour viewpoints no frontier
//                        viewpoint is near any more (their ISEs were
//                        covered) leave the tour, frontier viewpoints near no
//                        tour viewpoint (new ISEs) join it by cheapest
//                        insertion, and the order of the rest is kept
//                        (with pool_unknown_below, viewpoints that face
//                        little unknown space wait outside the tour),
//   leg                  a collision-checked LazyPRM* path from the UAV to the
//                        first tour viewpoint, re-planned when the map puts an
//                        obstacle on it (checkPath) or the target leaves the tour,
//   stop                 when no ISE of C_ins remains, or none of the
//                        remaining viewpoints can be reached: the decision
//                        says which.
//
// A target that cannot be reached (no path, or the leg ended away from it)
// counts a failure at its place; after max_failures failures, or after
// max_visits visits that left it in the frontier, every viewpoint within
// blacklist_radius of that place is ignored from then on and reported.
// Distances inside the cluster graph are straight lines, or with
// path_distances the planner's path-length oracle; legs are real paths.
// Deterministic for a seed and iteration-bounded path planning. Not thread-safe.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "surface_nbv/planning/cluster_graph.h"
#include "surface_nbv/planning/gaze_yaw.h"
#include "surface_nbv/planning/path_planner.h"
#include "surface_nbv/planning/reachable_space.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/util/point_hash.h"

namespace surface_nbv {

struct ExplorerConfig {
  ClusterGraphConfig graph;
  LinKernighanSolver::Config tsp;
  double match_radius = 1.0;      // m: a tour viewpoint is the same as a frontier one this close
  double reach_tolerance = 0.6;   // m: a finished leg this close to its target visited it
  int max_failures = 3;           // unreachable attempts before a place is blacklisted
  int max_visits = 2;             // visits that left a viewpoint in the frontier before blacklisting
  double blacklist_radius = 1.0;  // m
  int max_leg_attempts = 6;       // targets tried per decision before hovering
  bool always_full = false;       // recompute the whole tour on every frontier (comparison mode)
  // Path yaw: false interpolates from the start yaw to the target's along the
  // whole leg; true looks along the direction of travel on each segment and
  // turns to the target's yaw over the last turn_distance metres.
  bool travel_yaw = false;
  double turn_distance = 2.0;     // m
  // When a new target is due, the first head_lookahead tour viewpoints are
  // compared by eq. 5's utility for one viewpoint, |C_q| exp(-lambda_tc d),
  // d the straight distance from the UAV, and the best one is flown first
  // (the rest keep their order). 0 or 1: the tour's order as it is.
  int head_lookahead = 0;
  // The decay of that comparison per metre; < 0: lambda_tc.
  double head_lambda = -1.0;
  // The comparison measures d as sqrt(dx^2 + dy^2 + (s dz)^2) with s this
  // scale: above 1 a climb costs more than a move across.
  double head_vertical_scale = 1.0;
  // The comparison weighs |C_q| by the viewpoint's share of view rays that
  // meet unknown space (Viewpoint::unknown_fraction): of two viewpoints that
  // see as many ISEs, the one that also looks at more unseen space first.
  bool head_unknown = false;
  // travel_yaw only: between a leg's start and its final turn the UAV looks
  // where it sees the most ISEs of the frontier the leg was planned on
  // (gaze_yaw.h), along the leg where it sees fewer than gaze.min_ises.
  GazeConfig gaze;
  // A tour viewpoint must still see at least this many ISEs (|C_q|).
  int min_visible = 0;
  // While other viewpoints are in the tour, a viewpoint that faces less than
  // this share of unknown space (Viewpoint::unknown_fraction) does not join
  // it, and one that becomes the next target leaves it: leftovers wait until
  // the tour runs out (0: off). A tour of leftovers only (the end game) is
  // flown in its own order, with no head_lookahead comparison.
  double pool_unknown_below = 0.0;
  // Cluster-graph distances (q_l closest by path length): true uses the path
  // planner's oracle (straight line when free, else the roadmap's path
  // length, +inf when it connects nothing); false, straight lines.
  bool path_distances = false;
  // Before a leg is planned, the target must lie in the UAV's connected free
  // space (ReachableSpace, filled once per map version); one that does not
  // counts a failure at once instead of costing the planner its budget.
  bool check_reachable = false;
  // With check_reachable: each leg hands the planner the fill's shortest
  // way to the target (ReachableSpace::corridor) as a guide, followed when
  // the roadmap has no path, before its lattice and its growth. From inside
  // a deck to a target decks away the lattice, searching everything nearer
  // first, spent its node budget (seconds per leg, docs/scaling.md).
  bool corridor_guide = false;
  // The fill keeps cells whose centre is the planner's clearance (the
  // collision radius plus half a motion-check step, PathPlanner::clearance)
  // from obstacles: what the planner accepts.
  // A frontier without any ISE of C_ins before one was ever seen is a map
  // that has not seen enough yet, not a finished mission: a late first frame
  // (no ISE at all), or first frames whose ISEs all wait in C_rem because no
  // free space around them is known yet (dropped frames, a slow mapper).
  // The explorer hovers through this many such frontiers before it says
  // complete.
  int empty_updates_before_done = 10;
  // Wall seconds all leg attempts of one decision (update() or checkPath())
  // may take together; each plan() gets what is left (PathPlanner::plan's
  // max_seconds) and no attempt starts once it is spent: the decision
  // hovers and the next one goes on down the tour. Failing attempts at the
  // path budget each (max_leg_attempts of them, twice when the tour is
  // recomputed) held the ROS planner for minutes while the flight clock ran
  // on. 0: no limit (the headless runner's default: its clock waits).
  double leg_time_budget = 0.0;

  // Names the first bad key.
  Status validate() const;
};

enum class ExplorerAction {
  kContinue,  // keep flying the current leg
  kFly,       // fly `path` (a new leg)
  kHover,     // hold the current pose; nothing reachable right now
  kDone,      // the mission is over (see reason)
};

enum class ReplanReason {
  kNone,
  kInitial,            // first tour
  kTourFinished,       // every tour viewpoint visited: full recomputation
  kNewIses,            // new viewpoints joined the tour: local update
  kTargetCovered,      // the current target left the frontier: local update
  kTargetReached,      // the leg ended at its target: next leg
  kPathBlocked,        // an obstacle on the current leg
  kTargetUnreachable,  // no path to the target
  kRequested,          // replan() was called
  kComplete,           // no ISE of C_ins remains
  kNoReachableTarget,  // ISEs of C_ins remain, but no viewpoint can be reached
};

const char* toString(ExplorerAction action);
const char* toString(ReplanReason reason);

struct ExplorerTimings {
  double graph_ms = 0.0, tour_ms = 0.0, path_ms = 0.0, total_ms = 0.0;
};

struct ExplorerDecision {
  ExplorerAction action = ExplorerAction::kContinue;
  ReplanReason reason = ReplanReason::kNone;
  bool full_recompute = false;
  std::vector<Eigen::Vector4d> path;          // kFly: UAV -> target, [x, y, z, yaw]
  Eigen::Vector4d target = Eigen::Vector4d::Zero();
  PathStatus path_status = PathStatus::kExactSolution;  // of the last leg query
  ExplorerTimings timings;
  std::string message;
};

// An arc of the last full recomputation's tour: from the exit q_k of one
// cluster (or the UAV) to the entry q_l of the next, with its utility f_uv.
struct TourArc {
  Eigen::Vector3d from = Eigen::Vector3d::Zero(), to = Eigen::Vector3d::Zero();
  double utility = 0.0;
};

struct ExplorerStats {
  size_t full_recomputes = 0, local_updates = 0, legs = 0, leg_failures = 0;
  size_t targets_reached = 0, targets_covered = 0, paths_blocked = 0;
  size_t tour_viewpoints = 0, clusters = 0;
  size_t pooled = 0;            // pool_unknown_below: insertions skipped plus targets dropped
  size_t dropped_no_gain = 0;   // frontier viewpoints left out: fewer than min_visible ISEs in C_q
  size_t unreachable_skipped = 0;  // targets outside the UAV's free space (check_reachable)
  size_t gaze_vertices = 0;     // leg vertices whose yaw the gaze set
  size_t promoted = 0;          // head_lookahead: targets flown before the tour's head
  size_t budget_stops = 0;      // decisions that spent leg_time_budget before finding a leg
  size_t lattice_legs = 0;      // legs the path planner's lattice fallback found (path_lattice_step)
  size_t corridor_legs = 0;     // legs that follow the reachable space's corridor (corridor_guide)
  size_t roadmap_growths = 0;   // leg plans whose roadmap held no path and was sampled larger
  size_t roadmap_vertices = 0;  // the leg planner's roadmap after the last leg plan
  double tour_cost = 0.0;       // of the last full recomputation
  ExplorerTimings last;         // the last decision
};

class Explorer {
 public:
  // Both configs must validate(); the constructor trusts them.
  Explorer(const ExplorerConfig& config, const PathPlannerConfig& path_config);

  // The collision map legs are planned in (not owned) and the sampling bounds.
  Status setMap(const CollisionMap* map, const AlignedBox& bounds);
  // The collision map was updated: path validity is re-checked lazily.
  void mapChanged() {
    planner_.mapChanged();
    reach_filled_ = false;
  }

  // A new frontier (built on the current map), the UAV's configuration, and
  // whether the current leg has ended (the tracker finished it).
  ExplorerDecision update(const Frontier& frontier, const Eigen::Vector4d& uav, bool leg_finished);
  // Between frontiers: a new leg to the same target if the map now blocks the
  // current one, else kContinue.
  ExplorerDecision checkPath(const Eigen::Vector4d& uav);
  // The leg to the current target is no longer flown (the UAV was told to
  // hold): the next update() plans a new leg to the same target instead of
  // answering kContinue for a leg nobody flies. No failure is counted.
  void legCancelled() { have_target_ = false, path_.clear(); }
  // The next update() recomputes the whole tour.
  void replan() { tour_.clear(), have_target_ = false, requested_ = true; }
  // Forgets tour, failures and blacklist (the roadmap is kept).
  void reset();
  // head_lookahead ranks the first tour configurations by gain(q) exp(-lambda d)
  // with this gain instead of |C_q|, for diagnostics (nbv_mission
  // --oracle-gain). An empty function restores |C_q|.
  using HeadGain = std::function<double(const Eigen::Vector4d& q)>;
  void setHeadGain(HeadGain gain) { head_gain_ = std::move(gain); }

  const std::vector<Eigen::Vector4d>& tour() const { return tour_; }
  const std::vector<Eigen::Vector4d>& currentPath() const { return path_; }
  bool hasTarget() const { return have_target_; }
  const std::vector<Eigen::Vector3d>& blacklist() const { return blacklist_; }
  // The cluster-graph arcs the last full recomputation's tour uses.
  const std::vector<TourArc>& tourArcs() const { return arcs_; }
  const ExplorerStats& stats() const { return stats_; }
  const ExplorerConfig& config() const { return config_; }
  PathPlanner& pathPlanner() { return planner_; }
  const PathPlanner& pathPlanner() const { return planner_; }

 private:
  struct Place {
    Eigen::Vector3d position;
    int failures = 0, visits = 0;
  };
  Place& placeAt(const Eigen::Vector3d& p);
  bool blacklisted(const Eigen::Vector3d& p) const;
  void countFailure(const Eigen::Vector3d& p);
  // The frontier without blacklisted viewpoints nor ones that see fewer
  // than min_visible ISEs (clusters left empty are dropped).
  Frontier withoutBlacklisted(const Frontier& frontier, int min_visible = 0) const;
  // withoutBlacklisted with config().min_visible, or without it when that
  // would leave no cluster.
  Frontier plannable(const Frontier& frontier);
  bool fullRecompute(const Frontier& frontier, const Eigen::Vector4d& uav, ExplorerDecision* d);
  bool localUpdate(const Frontier& frontier, const Eigen::Vector4d& uav, ExplorerDecision* d);
  // A decision starts at t0: its leg attempts may run until t0 + leg_time_budget.
  void startLegBudget(std::chrono::steady_clock::time_point t0);
  bool pathBlocked(const Eigen::Vector4d& uav) const;
  // The point nearest p (within `within`) clear of the radius plus a cell,
  // written into q's first three coordinates.
  bool nearestFree(const Eigen::Vector3d& p, double within, Eigen::Vector4d* q) const;
  // planner_.plan(), its roadmap's growth counted in stats_.
  PathResult planLeg(const Eigen::Vector4d& from, const Eigen::Vector4d& to, double max_seconds,
                     const std::vector<Eigen::Vector3d>* guide = nullptr);
  void nextLeg(const Eigen::Vector4d& uav, ExplorerDecision* d);
  // The wanted viewpoints of the last frontier, hashed by position, with
  // their unknown_fraction (pool_unknown_below) and their gain in the
  // head_lookahead comparison (|C_q|, times unknown_fraction with head_unknown).
  struct WantedViewpoints {
    explicit WantedViewpoints(double cell) : hash(cell) {}
    PointHash hash;
    std::vector<double> unknown, gain;
  };
  // unknown_fraction of the wanted frontier viewpoint nearest p within match_radius (1: none).
  double unknownNear(const Eigen::Vector3d& p) const { return nearestValue(wanted_.unknown, p, 1.0); }
  // values[i] of the wanted viewpoint i nearest p within match_radius, else `none`.
  double nearestValue(const std::vector<double>& values, const Eigen::Vector3d& p, double none) const;
  // head_lookahead: moves the best of the first tour viewpoints to the front.
  void promoteBestHead(const Eigen::Vector4d& uav);
  // Applies travel_yaw to a leg ending at `target`.
  void orientLeg(std::vector<Eigen::Vector4d>* path, const Eigen::Vector4d& target) const;

  ExplorerConfig config_;
  PathPlanner planner_;
  AlignedBox bounds_;
  ReachableSpace reach_;
  bool reach_filled_ = false;  // for the current map version
  std::chrono::steady_clock::time_point leg_deadline_;  // of the current decision (leg_time_budget > 0)
  const CollisionMap* map_ = nullptr;
  double collision_radius_ = 1.0;
  std::vector<Eigen::Vector4d> tour_;   // front = current target while have_target_
  std::vector<Eigen::Vector4d> path_;   // current leg
  bool have_target_ = false;
  bool requested_ = false;
  bool seen_ises_ = false;      // some frontier held an ISE of C_ins
  int empty_updates_ = 0;       // frontiers without one while !seen_ises_
  std::vector<Place> places_;
  std::vector<Eigen::Vector3d> blacklist_;
  std::vector<TourArc> arcs_;
  WantedViewpoints wanted_;  // of the last frontier (head_lookahead, pool_unknown_below)
  std::vector<GazeTarget> gaze_targets_;                     // last frontier's ISEs of C_ins (gaze.enabled)
  HeadGain head_gain_;
  ExplorerStats stats_;
};

}  // namespace surface_nbv
