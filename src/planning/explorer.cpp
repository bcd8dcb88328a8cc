#include "surface_nbv/planning/explorer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/planning/tour_head.h"
#include "surface_nbv/util/angles.h"
#include "surface_nbv/util/point_hash.h"

namespace surface_nbv {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Frontier viewpoints worth visiting: in a cluster of positive gain.
bool wanted(const Frontier& f, size_t i) {
  const int32_t c = f.viewpoints[i].cluster;
  return c >= 0 && static_cast<size_t>(c) < f.clusters.size() && f.clusters[c].gain > 0.0;
}

Eigen::Vector4d configurationOf(const Viewpoint& v) {
  return Eigen::Vector4d(v.position.x(), v.position.y(), v.position.z(), v.yaw);
}

}  // namespace

Status ExplorerConfig::validate() const {
  if (Status s = graph.validate(); !s) return s;
  if (Status s = tsp.validate(); !s) return s;
  if (!(match_radius > 0.0) || !std::isfinite(match_radius)) return Status::Error("match_radius expected > 0");
  if (!(reach_tolerance > 0.0) || !std::isfinite(reach_tolerance)) return Status::Error("reach_tolerance expected > 0");
  if (max_failures < 1) return Status::Error("max_failures expected >= 1");
  if (max_visits < 1) return Status::Error("max_visits expected >= 1");
  if (!(blacklist_radius >= 0.0) || !std::isfinite(blacklist_radius)) {
    return Status::Error("blacklist_radius expected >= 0");
  }
  if (max_leg_attempts < 1) return Status::Error("max_leg_attempts expected >= 1");
  if (!(leg_time_budget >= 0.0) || !std::isfinite(leg_time_budget)) {
    return Status::Error("leg_time_budget expected >= 0 s (0: no limit)");
  }
  if (!(turn_distance >= 0.0) || !std::isfinite(turn_distance)) return Status::Error("turn_distance expected >= 0");
  if (head_lookahead < 0) return Status::Error("head_lookahead expected >= 0");
  if (!std::isfinite(head_lambda)) return Status::Error("head_lambda expected finite");
  if (!(head_vertical_scale >= 0.0 && std::isfinite(head_vertical_scale))) {
    return Status::Error("head_vertical_scale expected >= 0");
  }
  if (gaze.enabled) {
    if (!travel_yaw) return Status::Error("gaze expects travel_yaw (it turns the yaws travel_yaw sets)");
    if (Status s = gaze.validate(); !s) return s;
  }
  if (min_visible < 0) return Status::Error("min_visible expected >= 0");
  if (!(pool_unknown_below >= 0.0) || pool_unknown_below > 1.0) return Status::Error("pool_unknown_below expected in [0, 1]");
  if (empty_updates_before_done < 1) return Status::Error("empty_updates_before_done expected >= 1");
  return Status::Ok();
}

const char* toString(ExplorerAction action) {
  switch (action) {
    case ExplorerAction::kContinue: return "continue";
    case ExplorerAction::kFly: return "fly";
    case ExplorerAction::kHover: return "hover";
    case ExplorerAction::kDone: return "done";
  }
  return "unknown";
}

const char* toString(ReplanReason reason) {
  switch (reason) {
    case ReplanReason::kNone: return "none";
    case ReplanReason::kInitial: return "initial";
    case ReplanReason::kTourFinished: return "tour_finished";
    case ReplanReason::kNewIses: return "new_ises";
    case ReplanReason::kTargetCovered: return "target_covered";
    case ReplanReason::kTargetReached: return "target_reached";
    case ReplanReason::kPathBlocked: return "path_blocked";
    case ReplanReason::kTargetUnreachable: return "target_unreachable";
    case ReplanReason::kRequested: return "requested";
    case ReplanReason::kComplete: return "complete";
    case ReplanReason::kNoReachableTarget: return "no_reachable_target";
  }
  return "unknown";
}

Explorer::Explorer(const ExplorerConfig& config, const PathPlannerConfig& path_config)
    : config_(config),
      planner_(path_config),
      collision_radius_(path_config.collision_radius),
      wanted_(config.match_radius) {}

Status Explorer::setMap(const CollisionMap* map, const AlignedBox& bounds) {
  if (Status s = planner_.setMap(map, bounds); !s) return s;
  map_ = map;
  bounds_ = bounds;
  reach_filled_ = false;
  return Status::Ok();
}

void Explorer::reset() {
  tour_.clear();
  path_.clear();
  have_target_ = false;
  requested_ = false;
  places_.clear();
  blacklist_.clear();
  arcs_.clear();
  stats_ = ExplorerStats();
}

Explorer::Place& Explorer::placeAt(const Eigen::Vector3d& p) {
  for (Place& place : places_)
    if ((place.position - p).norm() <= config_.match_radius) return place;
  places_.push_back(Place{p});
  return places_.back();
}

bool Explorer::blacklisted(const Eigen::Vector3d& p) const {
  for (const Eigen::Vector3d& b : blacklist_)
    if ((b - p).norm() <= config_.blacklist_radius) return true;
  return false;
}

void Explorer::countFailure(const Eigen::Vector3d& p) {
  Place& place = placeAt(p);
  if (++place.failures == config_.max_failures) blacklist_.push_back(place.position);
}

Frontier Explorer::withoutBlacklisted(const Frontier& frontier, int min_visible) const {
  Frontier f = frontier;
  if (blacklist_.empty() && min_visible <= 0) return f;
  std::vector<Cluster> clusters;
  for (Viewpoint& v : f.viewpoints) v.cluster = -1;
  for (const Cluster& c : frontier.clusters) {
    Cluster kept = c;
    kept.viewpoints.clear();
    for (uint32_t i : c.viewpoints)
      if (!blacklisted(frontier.viewpoints[i].position) &&
          frontier.viewpoints[i].visible.size() >= static_cast<size_t>(std::max(0, min_visible))) {
        kept.viewpoints.push_back(i);
      }
    if (kept.viewpoints.empty()) continue;
    for (uint32_t i : kept.viewpoints) f.viewpoints[i].cluster = static_cast<int32_t>(clusters.size());
    clusters.push_back(std::move(kept));
  }
  f.clusters = std::move(clusters);
  return f;
}

Frontier Explorer::plannable(const Frontier& frontier) {
  Frontier f = withoutBlacklisted(frontier, config_.min_visible);
  size_t dropped = 0;
  for (size_t i = 0; i < frontier.viewpoints.size(); ++i) {
    dropped += frontier.viewpoints[i].cluster >= 0 && f.viewpoints[i].cluster < 0 &&
               !blacklisted(frontier.viewpoints[i].position);
  }
  stats_.dropped_no_gain = dropped;
  if (f.clusters.empty() && config_.min_visible > 0) f = withoutBlacklisted(frontier, 0);
  return f;
}

bool Explorer::fullRecompute(const Frontier& frontier, const Eigen::Vector4d& uav, ExplorerDecision* d) {
  const auto t0 = Clock::now();
  const DistanceFn distance =
      config_.path_distances ? DistanceFn(planner_.distanceOracle())
                             : DistanceFn([](const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm(); });
  const ClusterGraph graph(frontier, uav, distance, config_.graph);
  d->timings.graph_ms = msSince(t0);
  const auto t1 = Clock::now();
  const TourPlan plan = planTour(graph, config_.tsp);
  d->timings.tour_ms = msSince(t1);
  d->full_recompute = true;
  tour_.clear();
  have_target_ = false;
  path_.clear();
  ++stats_.full_recomputes;
  stats_.clusters = frontier.clusters.size();
  if (plan.status != TourPlanStatus::kOk) {
    d->message = std::string("tour: ") + toString(plan.status) + (plan.message.empty() ? "" : " " + plan.message);
    return false;
  }
  tour_ = plan.configurations;
  stats_.tour_cost = plan.cost;
  arcs_.clear();
  for (size_t i = 0; i < plan.clusters.size(); ++i) {
    const ClusterEdge& e = graph.edge(i == 0 ? 0 : plan.clusters[i - 1] + 1, plan.clusters[i] + 1);
    arcs_.push_back({e.q_k.head<3>(), graph.configuration(e.l_viewpoint).head<3>(), e.utility});
  }
  return !tour_.empty();
}

bool Explorer::localUpdate(const Frontier& frontier, const Eigen::Vector4d& uav, ExplorerDecision* d) {
  const auto t0 = Clock::now();
  const double r = config_.match_radius;
  PointHash viewpoints(r);
  for (size_t i = 0; i < frontier.viewpoints.size(); ++i)
    if (wanted(frontier, i)) viewpoints.add(frontier.viewpoints[i].position, static_cast<int>(i));
  // Tour viewpoints no wanted frontier viewpoint is near were covered.
  std::vector<char> matched(frontier.viewpoints.size(), 0);
  std::vector<Eigen::Vector4d> kept;
  for (size_t k = 0; k < tour_.size(); ++k) {
    bool near = false;
    viewpoints.any(tour_[k].head<3>(), r, [&](int i) {
      matched[i] = 1;
      near = true;
      return false;  // mark every match
    });
    if (near) {
      kept.push_back(tour_[k]);
    } else if (k == 0 && have_target_) {
      have_target_ = false;
      ++stats_.targets_covered;
      d->reason = ReplanReason::kTargetCovered;
    }
  }
  const bool removed = kept.size() != tour_.size();
  tour_ = std::move(kept);
  if (tour_.empty()) return false;
  // Wanted frontier viewpoints near no tour viewpoint are new: cheapest insertion.
  size_t inserted = 0;
  for (size_t i = 0; i < frontier.viewpoints.size(); ++i) {
    if (matched[i] || !wanted(frontier, i)) continue;
    if (frontier.viewpoints[i].unknown_fraction < config_.pool_unknown_below) {
      ++stats_.pooled;
      continue;
    }
    const Eigen::Vector4d q = configurationOf(frontier.viewpoints[i]);
    const Eigen::Vector3d x = q.head<3>();
    // Position p: before tour_[p]; tour_[0] stays first while it is the target.
    size_t best = tour_.size();
    double best_cost = (tour_.back().head<3>() - x).norm();
    for (size_t p = have_target_ ? 1 : 0; p < tour_.size(); ++p) {
      const Eigen::Vector3d a = p == 0 ? Eigen::Vector3d(uav.head<3>()) : Eigen::Vector3d(tour_[p - 1].head<3>());
      const Eigen::Vector3d b = tour_[p].head<3>();
      const double cost = (a - x).norm() + (x - b).norm() - (a - b).norm();
      if (cost < best_cost) best_cost = cost, best = p;
    }
    tour_.insert(tour_.begin() + static_cast<long>(best), q);
    ++inserted;
  }
  if (inserted > 0 && d->reason == ReplanReason::kNone) d->reason = ReplanReason::kNewIses;
  if (inserted > 0 || removed) ++stats_.local_updates;
  d->timings.tour_ms = msSince(t0);
  return true;
}

bool Explorer::pathBlocked(const Eigen::Vector4d& uav) const {
  if (map_ == nullptr || path_.size() < 2) return false;
  size_t start = 0;
  double closest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < path_.size(); ++i) {
    const double dist = (path_[i].head<3>() - uav.head<3>()).norm();
    if (dist < closest) closest = dist, start = i;
  }
  const double step = 0.5 * map_->cellSize();
  for (size_t i = start == 0 ? 1 : start; i < path_.size(); ++i) {
    const Eigen::Vector3d a = path_[i - 1].head<3>(), b = path_[i].head<3>();
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
    for (int s = 0; s <= n; ++s) {
      const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(s) / n);
      if ((p - uav.head<3>()).norm() < collision_radius_) continue;  // where the UAV already is
      if (!map_->isFree(p, collision_radius_)) return true;
    }
  }
  return false;
}

PathResult Explorer::planLeg(const Eigen::Vector4d& from, const Eigen::Vector4d& to, double max_seconds,
                             const std::vector<Eigen::Vector3d>* guide) {
  PathResult r = planner_.plan(from, to, max_seconds, guide);
  stats_.roadmap_growths += r.roadmap_grew ? 1 : 0;
  stats_.roadmap_vertices = planner_.roadmapVertices();
  return r;
}

bool Explorer::nearestFree(const Eigen::Vector3d& p, double within, Eigen::Vector4d* q) const {
  const double h = 0.5 * map_->cellSize();
  const int n = static_cast<int>(std::ceil(within / h));
  const double clearance = collision_radius_ + map_->cellSize();
  double best = std::numeric_limits<double>::infinity();
  for (int k = -n; k <= n; ++k)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i) {
        const Eigen::Vector3d c = p + h * Eigen::Vector3d(i, j, k);
        const double d = (c - p).norm();
        if (d <= within && d < best && map_->isFree(c, clearance)) best = d, q->head<3>() = c;
      }
  return std::isfinite(best);
}

double Explorer::nearestValue(const std::vector<double>& values, const Eigen::Vector3d& p, double none) const {
  const int i = wanted_.hash.nearest(p, config_.match_radius);
  return i < 0 ? none : values[static_cast<size_t>(i)];
}

void Explorer::promoteBestHead(const Eigen::Vector4d& uav) {
  const double lambda = config_.head_lambda >= 0.0 ? config_.head_lambda : config_.graph.lambda_tc;
  const auto gain = [this](const Eigen::Vector4d& q) {
    return head_gain_ ? head_gain_(q) : nearestValue(wanted_.gain, q.head<3>(), 0.0);
  };
  const size_t best = bestTourHead(tour_, uav, static_cast<size_t>(std::max(config_.head_lookahead, 0)), lambda,
                                   config_.head_vertical_scale, gain);
  if (best == 0) return;
  std::rotate(tour_.begin(), tour_.begin() + static_cast<std::ptrdiff_t>(best),
              tour_.begin() + static_cast<std::ptrdiff_t>(best) + 1);
  ++stats_.promoted;
}

void Explorer::startLegBudget(std::chrono::steady_clock::time_point t0) {
  leg_deadline_ = t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(config_.leg_time_budget));
}

void Explorer::nextLeg(const Eigen::Vector4d& uav, ExplorerDecision* d) {
  const auto t0 = Clock::now();
  Eigen::Vector4d from = uav;
  std::vector<Eigen::Vector4d> prefix;
  // A start the planner refuses (closer to an obstacle than the radius, or in
  // unknown space): leave by the shortest straight step to a free point.
  if (map_ != nullptr && !map_->isFree(uav.head<3>(), collision_radius_ + 0.5 * map_->cellSize())) {
    if (nearestFree(uav.head<3>(), 2.0, &from)) prefix.push_back(uav);
  }
  // pool_unknown_below: a next target that now faces little unknown space
  // leaves the tour while a viewpoint that faces more remains. When none does
  // (the mission's end game: only leftovers) the tour is flown in its own
  // order: pooling would leave only its last viewpoint, the far end of the
  // open path, each time, and the ranking would chase the last slivers of
  // unknown space from one end of the scene to the other.
  const auto facing = [this](const Eigen::Vector4d& q) {
    return unknownNear(q.head<3>()) >= config_.pool_unknown_below;
  };
  const bool end_game = config_.pool_unknown_below > 0.0 && std::none_of(tour_.begin(), tour_.end(), facing);
  while (config_.pool_unknown_below > 0.0 && !end_game && !have_target_ && tour_.size() > 1 &&
         !facing(tour_.front())) {
    tour_.erase(tour_.begin());
    ++stats_.pooled;
  }
  if (config_.head_lookahead > 1 && !have_target_ && !end_game) promoteBestHead(uav);
  const bool capped = config_.leg_time_budget > 0.0;
  auto left = [this, capped] {
    return capped ? std::chrono::duration<double>(leg_deadline_ - Clock::now()).count()
                  : std::numeric_limits<double>::infinity();
  };
  bool spent = false;
  Eigen::Vector3d last_target = from.head<3>();
  for (int attempt = 0; attempt < config_.max_leg_attempts && !tour_.empty(); ++attempt) {
    if (left() <= 0.0) {
      spent = true;
      break;
    }
    const Eigen::Vector4d target = tour_.front();
    last_target = target.head<3>();
    if (config_.check_reachable && map_ != nullptr) {
      if (!reach_filled_) reach_.fill(*map_, bounds_, from.head<3>(), planner_.clearance());
      reach_filled_ = true;
      if (!reach_.reachable(target.head<3>())) {
        countFailure(target.head<3>());
        ++stats_.leg_failures;
        ++stats_.unreachable_skipped;
        tour_.erase(tour_.begin());
        --attempt;  // cheap: does not use up an attempt (the tour shrinks)
        continue;
      }
    }
    std::vector<Eigen::Vector3d> guide;
    if (config_.corridor_guide && config_.check_reachable && map_ != nullptr) reach_.corridor(target.head<3>(), &guide);
    PathResult leg = planLeg(from, target, left(), &guide);
    // The frontier's clearance test and the planner's (radius plus half a
    // motion-check step) differ slightly: a target just inside the planner's
    // margin is moved to the nearest point that passes, within reach_tolerance.
    if (leg.status == PathStatus::kInvalidGoal && map_ != nullptr) {
      Eigen::Vector4d moved = target;
      if (nearestFree(target.head<3>(), config_.reach_tolerance, &moved)) leg = planLeg(from, moved, left(), &guide);
    }
    d->path_status = leg.status;
    if (hasPath(leg.status)) {
      path_ = prefix;
      path_.insert(path_.end(), leg.path.begin(), leg.path.end());
      orientLeg(&path_, target);
      if (config_.gaze.enabled) {
        stats_.gaze_vertices += applyGaze(config_.gaze, gaze_targets_, map_, config_.turn_distance + 0.1, &path_);
      }
      have_target_ = true;
      d->action = ExplorerAction::kFly;
      d->path = path_;
      d->target = target;
      ++stats_.legs;
      if (leg.from_lattice) ++stats_.lattice_legs;
      if (leg.from_guide) ++stats_.corridor_legs;
      d->timings.path_ms = msSince(t0);
      return;
    }
    if (leg.status == PathStatus::kInvalidStart) break;  // not the target's fault
    countFailure(target.head<3>());
    ++stats_.leg_failures;
    tour_.erase(tour_.begin());
  }
  have_target_ = false;
  path_.clear();
  d->action = ExplorerAction::kHover;
  if (d->reason == ReplanReason::kNone) d->reason = ReplanReason::kTargetUnreachable;
  char where[160];
  std::snprintf(where, sizeof(where), "no path from (%.1f, %.1f, %.1f) to a tour viewpoint (last: %s, to (%.1f, %.1f, %.1f))",
                from.x(), from.y(), from.z(), toString(d->path_status), last_target.x(), last_target.y(),
                last_target.z());
  d->message = where;
  if (spent) {
    ++stats_.budget_stops;
    d->message += "; leg_time_budget of " + std::to_string(config_.leg_time_budget) + " s spent";
  }
  d->timings.path_ms = msSince(t0);
}

void Explorer::orientLeg(std::vector<Eigen::Vector4d>* path, const Eigen::Vector4d& target) const {
  std::vector<Eigen::Vector4d>& p = *path;
  if (!config_.travel_yaw || p.size() < 2) return;
  // Heading of each segment; a (nearly) vertical one keeps the previous heading.
  const double start_yaw = p.front().w();
  double heading = start_yaw;
  std::vector<double> headings(p.size() - 1);
  for (size_t i = 0; i + 1 < p.size(); ++i) {
    const Eigen::Vector2d step = p[i + 1].head<2>() - p[i].head<2>();
    if (step.norm() > 0.2) heading = std::atan2(step.y(), step.x());
    headings[i] = heading;
  }
  // Vertex i looks along segment i; the last segment turns to the target's yaw
  // over its final turn_distance metres (all of it when shorter).
  for (size_t i = 0; i + 1 < p.size(); ++i) p[i].w() = headings[i];
  p.back().w() = target.w();
  const Eigen::Vector3d a = p[p.size() - 2].head<3>(), b = p.back().head<3>();
  const double last = (b - a).norm();
  if (last > config_.turn_distance + 0.1) {
    Eigen::Vector4d turn_point;
    turn_point << b + (a - b) * (config_.turn_distance / last), headings.back();
    p.insert(p.end() - 1, turn_point);
  } else if (p.size() == 2) {
    // One short segment: the UAV turns to its heading at the start (in
    // place), then to the target's yaw along all of it.
    return;
  }
}

ExplorerDecision Explorer::update(const Frontier& frontier, const Eigen::Vector4d& uav, bool leg_finished) {
  const auto t0 = Clock::now();
  startLegBudget(t0);
  ExplorerDecision d;
  if (leg_finished && have_target_ && !tour_.empty()) {
    const Eigen::Vector4d target = tour_.front();
    if ((uav.head<3>() - target.head<3>()).norm() <= config_.reach_tolerance) {
      ++stats_.targets_reached;
      Place& place = placeAt(target.head<3>());
      if (++place.visits == config_.max_visits) blacklist_.push_back(place.position);
      d.reason = ReplanReason::kTargetReached;
    } else {
      countFailure(target.head<3>());
      ++stats_.leg_failures;
      d.reason = ReplanReason::kTargetUnreachable;
    }
    tour_.erase(tour_.begin());
    have_target_ = false;
    path_.clear();
  }
  seen_ises_ = seen_ises_ || !frontier.complete();
  if (!seen_ises_ && ++empty_updates_ < config_.empty_updates_before_done) {
    d.action = ExplorerAction::kHover;
    d.message = "no ISE of C_ins observed yet (" + std::to_string(empty_updates_) + " frontier(s) without one, " +
                std::to_string(frontier.remaining) + " ISE(s) in C_rem)";
    d.timings.total_ms = msSince(t0);
    stats_.last = d.timings;
    return d;
  }
  if (frontier.complete()) {
    tour_.clear();
    path_.clear();
    have_target_ = false;
    d.action = ExplorerAction::kDone;
    d.reason = ReplanReason::kComplete;
    d.message = "no ISE of C_ins remains (" + std::to_string(frontier.remaining) + " in C_rem)";
    d.timings.total_ms = msSince(t0);
    stats_.last = d.timings;
    return d;
  }
  const Frontier f = plannable(frontier);
  if (config_.gaze.enabled) gaze_targets_ = gazeTargets(frontier);
  if (config_.head_lookahead > 1 || config_.pool_unknown_below > 0.0) {
    wanted_.hash.clear(), wanted_.unknown.clear(), wanted_.gain.clear();
    for (size_t i = 0; i < f.viewpoints.size(); ++i)
      if (wanted(f, i)) {
        const Viewpoint& v = f.viewpoints[i];
        wanted_.hash.add(v.position, static_cast<int>(wanted_.unknown.size()));
        wanted_.unknown.push_back(v.unknown_fraction);
        wanted_.gain.push_back(v.visible.size() * (config_.head_unknown ? v.unknown_fraction : 1.0));
      }
  }
  // Def. 2 read with what the flight has shown: an ISE whose viewpoint is
  // blacklisted (unreachable, or visited max_visits times without completing
  // it) has no collision-free configuration that completes it, so it joins C_rem.
  size_t open = 0;
  for (const Ise& ise : frontier.ises) {
    if (ise.remaining || ise.viewpoint < 0 || static_cast<size_t>(ise.viewpoint) >= frontier.viewpoints.size()) continue;
    const Viewpoint& v = frontier.viewpoints[ise.viewpoint];
    open += v.cluster >= 0 && !blacklisted(v.position);
  }
  if (open == 0 && !blacklist_.empty()) {
    tour_.clear();
    path_.clear();
    have_target_ = false;
    d.action = ExplorerAction::kDone;
    d.reason = ReplanReason::kComplete;
    d.message = "no ISE of C_ins remains (" + std::to_string(frontier.remaining) + " in C_rem, " +
                std::to_string(frontier.insideCount()) + " more at " + std::to_string(blacklist_.size()) +
                " blacklisted place(s))";
    d.timings.total_ms = msSince(t0);
    stats_.last = d.timings;
    return d;
  }
  const bool initial = stats_.full_recomputes == 0;
  bool have_tour = false;
  if (!tour_.empty() && !config_.always_full) have_tour = localUpdate(f, uav, &d);
  if (!have_tour) {
    if (d.reason == ReplanReason::kNone || d.reason == ReplanReason::kTargetReached) {
      d.reason = requested_ ? ReplanReason::kRequested : initial ? ReplanReason::kInitial : ReplanReason::kTourFinished;
    }
    requested_ = false;
    have_tour = fullRecompute(f, uav, &d);
  }
  if (!have_tour) {
    d.action = ExplorerAction::kDone;
    d.reason = ReplanReason::kNoReachableTarget;
    d.message = std::to_string(frontier.insideCount()) + " ISE(s) of C_ins remain but no viewpoint can be reached; " +
                std::to_string(blacklist_.size()) + " place(s) blacklisted; " + d.message;
  } else if (have_target_ && !pathBlocked(uav)) {
    d.action = ExplorerAction::kContinue;
  } else {
    if (have_target_) {
      ++stats_.paths_blocked;
      d.reason = ReplanReason::kPathBlocked;
    }
    nextLeg(uav, &d);
    // Every target failed: the tour is empty; one full recomputation more.
    if (d.action == ExplorerAction::kHover && tour_.empty() && fullRecompute(plannable(frontier), uav, &d)) {
      nextLeg(uav, &d);
    }
  }
  stats_.tour_viewpoints = tour_.size();
  d.timings.total_ms = msSince(t0);
  stats_.last = d.timings;
  return d;
}

ExplorerDecision Explorer::checkPath(const Eigen::Vector4d& uav) {
  const auto t0 = Clock::now();
  startLegBudget(t0);
  ExplorerDecision d;
  if (have_target_ && pathBlocked(uav)) {
    ++stats_.paths_blocked;
    d.reason = ReplanReason::kPathBlocked;
    nextLeg(uav, &d);
  }
  d.timings.total_ms = msSince(t0);
  return d;
}

}  // namespace surface_nbv
