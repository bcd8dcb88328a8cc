#include "surface_nbv/mission/oracle_planner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <queue>
#include <random>

#include "surface_nbv/eval/free_space_grid.h"
#include "surface_nbv/eval/surface_sampler.h"
#include "surface_nbv/planning/open_path.h"
#include "surface_nbv/planning/reachable_space.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/tracking/trajectory.h"
#include "surface_nbv/tracking/uav_model.h"
#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kLegAttempts = 10;  // plan() calls per leg before its viewpoint is skipped

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string format(const char* fmt, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), fmt, a, b, c, d);
  return buf;
}

// Voxel index range [lo, hi] of the box [a, b], clamped to the grid.
void voxelRange(const TsdfMap& map, const Eigen::Vector3d& a, const Eigen::Vector3d& b, Eigen::Vector3i* lo,
                Eigen::Vector3i* hi) {
  const Eigen::Vector3d origin = map.config().bounds.min;
  const Eigen::Vector3i top = map.gridVoxels() - Eigen::Vector3i::Ones();
  *lo = ((a - origin) / map.voxelSize()).array().floor().cast<int>().max(0).min(top.array());
  *hi = ((b - origin) / map.voxelSize()).array().floor().cast<int>().max(0).min(top.array());
}

}  // namespace

// The candidates that passed the filters, as poses of base_link.
struct OraclePlanner::Candidates {
  std::vector<Eigen::Vector4d> poses;
};

Status OracleConfig::validate() const {
  if (Status s = camera.validate(); !s) return Status::Error("camera: " + s.message());
  if (Status s = tsdf.validate(); !s) return Status::Error("tsdf: " + s.message());
  if (Status s = collision.validate(); !s) return Status::Error("collision: " + s.message());
  if (Status s = path.validate(); !s) return Status::Error("path: " + s.message());
  if (!start.allFinite() || !tsdf.bounds.contains(start.head<3>()))
    return Status::Error("start expected finite and inside the map bounds");
  if (!(delta_pose > 0.0)) return Status::Error("delta_pose expected > 0");
  if (offset_fractions.empty()) return Status::Error("offset_fractions expected non-empty");
  for (double f : offset_fractions)
    if (!(f > 0.0 && f <= 2.0)) return Status::Error("offset_fractions expected each in (0, 2]");
  if (!(target_spacing > 0.0)) return Status::Error("target_spacing expected > 0");
  if (!(candidate_spacing > 0.0)) return Status::Error("candidate_spacing expected > 0");
  if (max_candidates < 1) return Status::Error("max_candidates expected >= 1");
  if (!(depth_tolerance_voxels > 0.0)) return Status::Error("depth_tolerance_voxels expected > 0");
  if (!(max_incidence_deg > 0.0 && max_incidence_deg <= 90.0))
    return Status::Error("max_incidence_deg expected in (0, 90]");
  if (!(vfov_margin_deg >= 0.0 && vfov_margin_deg < 0.5 * camera.vfov_deg))
    return Status::Error("vfov_margin_deg expected in [0, vfov_deg / 2)");
  if (!(cover_fraction > 0.0 && cover_fraction <= 1.0)) return Status::Error("cover_fraction expected in (0, 1]");
  if (path_iterations < 1) return Status::Error("path_iterations expected >= 1");
  if (!(path_time_limit > 0.0)) return Status::Error("path_time_limit expected > 0");
  if (!(speed > 0.0)) return Status::Error("speed expected > 0");
  if (!(yaw_rate > 0.0)) return Status::Error("yaw_rate expected > 0");
  if (threads < 1) return Status::Error("threads expected >= 1");
  return Status::Ok();
}

OracleConfig oracleConfigFrom(const MissionConfig& mission) {
  OracleConfig c;
  c.camera = mission.camera;
  c.camera.noise_k = 0.0;  // the oracle sees the true surface
  c.camera.sensor = SensorModelConfig();
  c.tsdf = mission.tsdf;
  c.collision = mission.collision;
  c.path = mission.path;
  c.start = mission.start;
  c.delta_pose = mission.surface.delta_pose;
  c.speed = mission.speed;
  c.yaw_rate = mission.yaw_rate;
  c.threads = std::max(1, mission.threads);
  c.seed = mission.seed;
  return c;
}

OraclePlanner::OraclePlanner(const OracleConfig& config, const TriangleMesh& mesh, const RaycastScene& scene)
    : config_(config), mesh_(mesh), scene_(scene) {}

OraclePlanner::~OraclePlanner() = default;

void OraclePlanner::say(const std::string& line) const {
  if (progress_) progress_(line);
}

// Every voxel in the bounds known free, then the voxels whose centre lies
// within half a voxel diagonal of a triangle occupied: the surface is closed
// in voxels wherever the mesh is.
void OraclePlanner::buildMap() {
  map_ = std::make_unique<TsdfMap>(config_.tsdf);
  const float w = std::max(config_.tsdf.w_th, 1.0f);
  const float free_phi = static_cast<float>(config_.tsdf.truncationDistance());
  const Eigen::Vector3i blocks = map_->gridBlocks();
  map_->beginChange();
  for (int z = 0; z < blocks.z(); ++z)
    for (int y = 0; y < blocks.y(); ++y)
      for (int x = 0; x < blocks.x(); ++x)
        if (TsdfBlock* b = map_->allocateBlock(Eigen::Vector3i(x, y, z)))
          b->voxels.fill(TsdfVoxel{free_phi, w});
  const double half_diagonal = 0.5 * std::sqrt(3.0) * map_->voxelSize();
  const double r2 = half_diagonal * half_diagonal;
  for (const Eigen::Vector3i& t : mesh_.triangles) {
    const Eigen::Vector3d a = mesh_.vertices[t[0]].cast<double>(), b = mesh_.vertices[t[1]].cast<double>(),
                          c = mesh_.vertices[t[2]].cast<double>();
    const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c).array() - half_diagonal;
    const Eigen::Vector3d hi = a.cwiseMax(b).cwiseMax(c).array() + half_diagonal;
    if ((hi.array() < config_.tsdf.bounds.min.array()).any() || (lo.array() > config_.tsdf.bounds.max.array()).any())
      continue;
    Eigen::Vector3i vlo, vhi;
    voxelRange(*map_, lo, hi, &vlo, &vhi);
    for (int z = vlo.z(); z <= vhi.z(); ++z)
      for (int y = vlo.y(); y <= vhi.y(); ++y)
        for (int x = vlo.x(); x <= vhi.x(); ++x) {
          const Eigen::Vector3i v(x, y, z);
          if (squaredDistanceToTriangle(map_->voxelCenter(v), a, b, c) > r2) continue;
          if (TsdfVoxel* voxel = map_->allocateVoxel(v)) voxel->phi = 0.0f;
        }
  }
  collision_ = std::make_unique<CollisionMap>(*map_, config_.collision);
}

void OraclePlanner::buildCandidates(Candidates* out, OracleResult* r) const {
  SurfaceCloud source;
  if (Status s = SurfaceSampler(config_.candidate_spacing, config_.seed + 1, config_.threads)
                     .sample(mesh_, config_.max_targets, &source);
      !s) {
    r->status = Status::Error("candidate samples: " + s.message());
    return;
  }
  const double cell = collision_->cellSize();
  // The free space connected to the start through collision cells whose
  // centre passes the path planner's own test (isFree at its clearance, the
  // radius plus half its motion-check step, PathPlanner::clearance()): the
  // explorer's quicker test lets through passages the planner cannot fly. A
  // start whose own cell is not clear seeds from the clear ones of the 26
  // around it (1.75 cells: at most one cell along each axis).
  const double step = config_.path.validity_resolution > 0.0 ? config_.path.validity_resolution : 0.5 * cell;
  ReachableSpace reach;
  reach.fill(*collision_, config_.tsdf.bounds, config_.start.head<3>(), config_.path.collision_radius + 0.5 * step,
             0.0, 1.75 * cell, ReachableSpace::Clear::kPlannerTest);
  if (!reach.seeded()) {
    r->status = Status::Error("the start is not clear: no collision cell at or next to it has the planner's clearance");
    return;
  }
  const double clearance = config_.path.collision_radius + cell;
  const double max_elevation = config_.camera.maxPoseElevationDeg(config_.vfov_margin_deg) * M_PI / 180.0;
  const double min_elevation = config_.camera.minPoseElevationDeg(config_.vfov_margin_deg) * M_PI / 180.0;
  std::mt19937_64 rng(config_.seed);
  std::uniform_real_distribution<double> azimuth(-M_PI, M_PI);
  std::vector<Eigen::Vector4d> kept;
  for (size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector3d s = source.points[i].cast<double>();
    for (int side : {1, -1}) {
      const Eigen::Vector3d m = side * source.normals[i].cast<double>();
      const double horizontal = m.head<2>().norm();
      // The camera cannot look straight down: an upward normal gets a
      // seeded azimuth and every elevation is clamped into the vertical FOV.
      const double az = horizontal > 1e-3 ? std::atan2(m.y(), m.x()) : azimuth(rng);
      const double el = std::clamp(std::atan2(m.z(), horizontal), min_elevation, max_elevation);
      for (double f : config_.offset_fractions) {
        // A pose in collision (e.g. below a sample near the floor) is tried
        // again from above, then from below, at the FOV's edge.
        const double tilts[3] = {el, max_elevation, min_elevation};
        for (int k = 0; k < 3; ++k) {
          const double tilt = tilts[k];
          if (k > 0 && tilt == el) continue;
          const Eigen::Vector3d dir(std::cos(tilt) * std::cos(az), std::cos(tilt) * std::sin(az), std::sin(tilt));
          const Eigen::Vector3d p = s + f * config_.delta_pose * dir;
          if (!config_.tsdf.bounds.contains(p)) continue;
          ++r->candidates_built;
          if (!collision_->isFree(p, clearance) || !reach.reachable(p)) continue;
          kept.emplace_back(p.x(), p.y(), p.z(), wrapAngle(az + M_PI));
          break;
        }
      }
    }
  }
  if (kept.size() > config_.max_candidates) {
    std::vector<size_t> index(kept.size());
    for (size_t i = 0; i < index.size(); ++i) index[i] = i;
    std::shuffle(index.begin(), index.end(), rng);
    index.resize(config_.max_candidates);
    std::sort(index.begin(), index.end());
    for (size_t i : index) out->poses.push_back(kept[i]);
  } else {
    out->poses = std::move(kept);
  }
  r->candidates = out->poses.size();
}

std::vector<std::vector<uint32_t>> OraclePlanner::visibility(const Candidates& c,
                                                             const std::vector<Eigen::Vector3d>& targets,
                                                             const std::vector<Eigen::Vector3d>& normals) const {
  const DepthCamera camera(config_.camera);
  const DepthRenderer renderer(scene_, camera, 1);
  const double tol = config_.depth_tolerance_voxels * config_.tsdf.voxel_size;
  const double cos_max = std::cos(config_.max_incidence_deg * M_PI / 180.0);
  const double th = std::tan(0.5 * config_.camera.hfov_deg * M_PI / 180.0);
  const double tv = std::tan(0.5 * config_.camera.vfov_deg * M_PI / 180.0);
  const double far2 = config_.camera.max_range * config_.camera.max_range * (1.0 + th * th + tv * tv);
  std::vector<std::vector<uint32_t>> seen(c.poses.size());
  parallelFor(c.poses.size(), config_.threads, [&](size_t i) {
    Viewpoint vp;
    vp.position = c.poses[i].head<3>();
    vp.yaw = c.poses[i].w();
    const Transform T_W_C = vp.cameraPose(config_.camera);
    const Transform T_C_W = T_W_C.inverse();
    DepthImage image;
    renderer.render(T_W_C, &image);
    for (size_t j = 0; j < targets.size(); ++j) {
      const Eigen::Vector3d ray = vp.position - targets[j];
      const double d2 = ray.squaredNorm();
      if (d2 > far2 || d2 <= 0.0) continue;
      if (std::abs(normals[j].dot(ray)) < cos_max * std::sqrt(d2)) continue;
      const Eigen::Vector3d p_C = T_C_W * targets[j];
      double col = 0.0, row = 0.0;
      if (!camera.sees(p_C) || !camera.project(p_C, &col, &row)) continue;
      const int u = static_cast<int>(std::lround(col)), v = static_cast<int>(std::lround(row));
      static const int kNear[5][2] = {{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      for (const auto& k : kNear) {
        const int uu = u + k[0], vv = v + k[1];
        if (uu < 0 || vv < 0 || uu >= image.width || vv >= image.height) continue;
        const float z = image.at(vv, uu);
        if (std::isfinite(z) && std::abs(z - p_C.z()) <= tol) {
          seen[i].push_back(static_cast<uint32_t>(j));
          break;
        }
      }
    }
  });
  return seen;
}

void OraclePlanner::tour(OracleResult* r) {
  const int n = static_cast<int>(r->viewpoints.size()) + 1;
  auto node = [&](int k) -> Eigen::Vector3d {
    return k == 0 ? Eigen::Vector3d(config_.start.head<3>()) : Eigen::Vector3d(r->viewpoints[k - 1].head<3>());
  };
  CostMatrix costs(n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (a != b) costs.at(a, b) = (node(a) - node(b)).norm();
  const Clock::time_point t0 = Clock::now();
  LinKernighanSolver::Config lk;
  lk.seed = config_.seed;
  const TourResult t = solveOpenPath(costs, 0, lk);
  r->tour_status = t.status;
  r->times.tour = msSince(t0);
  if (!hasTour(t.status)) {
    r->status = Status::Error(std::string("tour: ") + toString(t.status) + " " + t.message);
    return;
  }
  r->tour_length = t.cost;
  for (size_t k = 1; k < t.tour.size(); ++k) r->order.push_back(t.tour[k] - 1);

  PathPlannerConfig pc = config_.path;
  pc.iteration_budget = config_.path_iterations;
  pc.time_budget = config_.path_time_limit;
  pc.seed = config_.seed;
  pc.stop_at_first_solution = !config_.refine_paths;
  PathPlanner planner(pc);
  if (Status s = planner.setMap(collision_.get(), config_.tsdf.bounds); !s) {
    r->status = Status::Error("path planner: " + s.message());
    return;
  }
  Eigen::Vector4d here = config_.start;
  r->path = {here};
  r->path_viewpoint = {-1};
  for (size_t k = 0; k < r->order.size(); ++k) {
    const Eigen::Vector4d goal = r->viewpoints[r->order[k]];
    PathResult leg;
    if ((goal.head<3>() - here.head<3>()).norm() < 1e-9) {
      leg.status = PathStatus::kExactSolution;
      leg.path = {here, goal};
    }
    // The roadmap persists: each retry adds path_iterations samples to it.
    for (int attempt = 0; attempt < kLegAttempts && !hasPath(leg.status); ++attempt) leg = planner.plan(here, goal);
    if (!hasPath(leg.status)) {
      ++r->failed_legs;
      say(format("  leg %.0f: no path, viewpoint skipped", double(k)) + " (" + toString(leg.status) + ")");
      continue;
    }
    for (size_t i = 1; i < leg.path.size(); ++i) {
      r->path.push_back(leg.path[i]);
      r->path_viewpoint.push_back(i + 1 == leg.path.size() ? r->order[k] : -1);
      r->path_length += (leg.path[i].head<3>() - leg.path[i - 1].head<3>()).norm();
    }
    here = r->path.back();
    if ((k + 1) % 50 == 0) say(format("  legs %.0f / %.0f, path %.1f m", double(k + 1), double(r->order.size()),
                                      r->path_length));
  }
  std::vector<Waypoint> waypoints;
  for (const Eigen::Vector4d& q : r->path) waypoints.push_back({q.head<3>(), q.w()});
  r->timed = timeWaypoints(waypoints, 0.0, config_.speed, config_.yaw_rate);
  r->flight_time = r->timed.endTime() - r->timed.startTime();
}

OracleResult OraclePlanner::plan() {
  const Clock::time_point t_all = Clock::now();
  OracleResult r;
  if (Status s = config_.validate(); !s) {
    r.status = s;
    return r;
  }
  // 1. Targets on the true surface.
  Clock::time_point t0 = Clock::now();
  SurfaceCloud cloud;
  if (Status s = SurfaceSampler(config_.target_spacing, config_.seed, config_.threads)
                     .sample(mesh_, config_.max_targets, &cloud);
      !s) {
    r.status = Status::Error("targets: " + s.message());
    return r;
  }
  std::vector<Eigen::Vector3d> targets(cloud.size()), normals(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i) {
    targets[i] = cloud.points[i].cast<double>();
    normals[i] = cloud.normals[i].cast<double>();
  }
  r.targets = targets.size();
  r.times.targets = msSince(t0);
  say(format("targets: %.0f at %.2f m spacing", double(r.targets), config_.target_spacing));

  // 2. The perfect-knowledge map.
  t0 = Clock::now();
  buildMap();
  r.times.map = msSince(t0);
  const double cell = collision_->cellSize();
  if (!collision_->isFree(config_.start.head<3>(), config_.path.collision_radius + 0.25 * cell)) {
    r.status = Status::Error("start is in collision in the perfect map");
    return r;
  }
  say(format("perfect map: %.0f blocks, collision cell %.2f m, %.1f s", double(map_->numBlocks()), cell,
             r.times.map / 1000.0));

  // 3. Candidate viewpoints.
  t0 = Clock::now();
  Candidates candidates;
  buildCandidates(&candidates, &r);
  if (!r.status) return r;
  r.times.candidates = msSince(t0);
  say(format("candidates: %.0f kept of %.0f built in the bounds, %.1f s", double(r.candidates),
             double(r.candidates_built), r.times.candidates / 1000.0));
  if (candidates.poses.empty()) {
    r.status = Status::Error("no collision-free, reachable candidate viewpoint");
    return r;
  }

  // 4. What each candidate sees.
  t0 = Clock::now();
  const std::vector<std::vector<uint32_t>> seen = visibility(candidates, targets, normals);
  std::vector<uint8_t> coverable(targets.size(), 0);
  for (const auto& s : seen)
    for (uint32_t j : s) coverable[j] = 1;
  for (size_t j = 0; j < targets.size(); ++j)
    if (coverable[j]) ++r.coverable;
    else r.uncoverable.push_back(targets[j]);
  r.times.visibility = msSince(t0);
  say(format("visibility: %.0f coverable targets, %.0f seen by no candidate, %.1f s", double(r.coverable),
             double(r.uncoverable.size()), r.times.visibility / 1000.0));

  // 5. Greedy set cover, lazy: a gain only shrinks as targets get covered.
  t0 = Clock::now();
  const size_t goal = static_cast<size_t>(std::ceil(config_.cover_fraction * r.coverable - 1e-9));
  std::vector<uint8_t> covered(targets.size(), 0);
  std::priority_queue<std::pair<size_t, long>> queue;  // (gain, -index): ties to the lower index
  for (size_t i = 0; i < seen.size(); ++i)
    if (!seen[i].empty()) queue.push({seen[i].size(), -static_cast<long>(i)});
  while (r.covered < goal && !queue.empty()) {
    const auto [stale, neg] = queue.top();
    queue.pop();
    const size_t i = static_cast<size_t>(-neg);
    size_t gain = 0;
    for (uint32_t j : seen[i]) gain += covered[j] ? 0 : 1;
    if (gain == 0) continue;
    if (gain < stale) {
      queue.push({gain, neg});
      continue;
    }
    for (uint32_t j : seen[i]) covered[j] = 1;
    r.covered += gain;
    r.viewpoints.push_back(candidates.poses[i]);
    r.gains.push_back(gain);
  }
  r.times.cover = msSince(t0);
  say(format("set cover: %.0f viewpoints cover %.0f of %.0f coverable targets (%.2f %%)", double(r.viewpoints.size()),
             double(r.covered), double(r.coverable), 100.0 * r.coveredFraction()));

  // 6. The tour and its real path.
  t0 = Clock::now();
  tour(&r);
  r.times.paths = msSince(t0) - r.times.tour;
  r.times.total = msSince(t_all);
  if (r.status)
    say(format("tour: straight %.1f m, path %.1f m, flight %.1f min, %.1f s", r.tour_length, r.path_length,
               r.flight_time / 60.0, r.times.paths / 1000.0));
  return r;
}

}  // namespace surface_nbv
