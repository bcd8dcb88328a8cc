#include "surface_nbv/eval/evaluator.h"

#include <chrono>
#include <cmath>
#include <memory>

#include "surface_nbv/eval/free_space_grid.h"
#include "surface_nbv/eval/m3c2_distance.h"
#include "surface_nbv/eval/point_index.h"
#include "surface_nbv/eval/visibility_pruner.h"
#include "surface_nbv/sim/raycast_scene.h"

namespace surface_nbv {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

Status Evaluator::evaluate(const TriangleMesh& ground_truth, const TriangleMesh& reconstruction,
                           EvalResult* result) const {
  EvalResult r;
  if (Status s = prepareGroundTruth(ground_truth, &r); !s) return s;
  if (Status s = scoreReconstruction(reconstruction, &r); !s) return s;
  *result = std::move(r);
  return Status::Ok();
}

Status Evaluator::prepareGroundTruth(const TriangleMesh& ground_truth, EvalResult* result) const {
  if (Status s = config_.validate(); !s) return s;
  if (!(ground_truth.area() > 0.0)) return Status::Error("ground truth has no surface to evaluate against");
  const auto t_start = Clock::now();
  EvalResult r;
  r.config = config_;
  r.ground_truth_triangles = ground_truth.numTriangles();
  r.ground_truth_area = ground_truth.area();

  auto t = Clock::now();
  const SurfaceSampler sampler(config_.spacing(), config_.seed, config_.threads);
  if (Status s = sampler.sample(ground_truth, config_.max_points, &r.ground_truth); !s) {
    return Status::Error("ground truth: " + s.message());
  }
  r.timings.ground_truth_sample_s = secondsSince(t);

  r.sensor_bounds = config_.sensorBounds(ground_truth.bounds());
  if (config_.prune_hidden) {
    t = Clock::now();
    FreeSpaceGrid free_space;
    if (Status s = free_space.build(ground_truth, r.sensor_bounds, config_.free_space_cell, config_.collision_radius,
                                    config_.threads);
        !s) {
      return s;
    }
    r.free_space_cells = free_space.numCells() - free_space.numBlocked();
    r.reachable_cells = free_space.numReachable();
    std::unique_ptr<RaycastScene> scene;
    if (Status s = RaycastScene::create(ground_truth, &scene); !s) return s;
    r.timings.free_space_s = secondsSince(t);
    t = Clock::now();
    VisibilityPruner(*scene, free_space, config_).prune(&r.ground_truth, &r.visible);
    r.timings.visibility_s = secondsSince(t);
  } else {
    r.visible.assign(r.ground_truth.size(), 1);
  }
  r.timings.ground_truth_s = secondsSince(t_start);
  *result = std::move(r);
  return Status::Ok();
}

Status Evaluator::scoreReconstruction(const TriangleMesh& reconstruction, EvalResult* result) const {
  EvalResult& r = *result;
  if (r.ground_truth.size() == 0 || r.visible.size() != r.ground_truth.size()) {
    return Status::Error("scoreReconstruction: the ground-truth side is not prepared");
  }
  const auto t_start = Clock::now();
  r.reconstruction_triangles = reconstruction.numTriangles();
  r.reconstruction_area = reconstruction.area();
  auto t = Clock::now();
  const SurfaceSampler sampler(config_.spacing(), config_.seed, config_.threads);
  if (Status s = sampler.sample(reconstruction, config_.max_points, &r.reconstruction); !s) {
    return Status::Error("reconstruction: " + s.message());
  }
  r.timings.sample_s = r.timings.ground_truth_sample_s + secondsSince(t);

  t = Clock::now();
  const PointIndex reconstruction_index(r.reconstruction.points);
  r.coverage = computeCoverage(r.ground_truth, r.visible, reconstruction_index, config_.eMax(), config_.threads);
  r.timings.coverage_s = secondsSince(t);

  t = Clock::now();
  r.error.assign(r.ground_truth.size(), std::nanf(""));
  if (r.coverage.num_covered > 0) {
    const PointIndex ground_truth_index(r.ground_truth.points, &r.visible);
    r.error = M3c2Distance(config_).compute(r.ground_truth, ground_truth_index, r.reconstruction, reconstruction_index,
                                            r.coverage.covered);
  }
  r.error_stats = ErrorStats::of(r.error);
  r.matched = r.error_stats.count;
  r.timings.m3c2_s = secondsSince(t);
  r.timings.total_s = r.timings.ground_truth_s + secondsSince(t_start);
  return Status::Ok();
}

}  // namespace surface_nbv
