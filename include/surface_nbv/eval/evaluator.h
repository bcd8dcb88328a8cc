// Evaluates a reconstructed mesh against a ground-truth mesh, both in the
// world frame (docs/method.md, "Evaluation protocol"): samples both surfaces,
// prunes the ground truth to what a sensor in reachable free space can see,
// measures coverage within e_max and the M3C2-like signed error of the
// covered samples. ROS-free, for nbv_evaluate and the mission runner alike.
// Stateless apart from its config; uses config.threads; results repeat
// exactly whatever the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "surface_nbv/eval/coverage.h"
#include "surface_nbv/eval/error_stats.h"
#include "surface_nbv/eval/eval_config.h"
#include "surface_nbv/eval/surface_sampler.h"
#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct EvalTimings {
  double sample_s = 0.0, free_space_s = 0.0, visibility_s = 0.0, coverage_s = 0.0, m3c2_s = 0.0, total_s = 0.0;
  // The ground-truth side's share (prepareGroundTruth), which every scoring
  // adds to its own: its sampling, and all of it.
  double ground_truth_sample_s = 0.0, ground_truth_s = 0.0;
};

struct EvalResult {
  EvalConfig config;         // as used
  AlignedBox sensor_bounds;  // where sensor positions were looked for
  size_t ground_truth_triangles = 0, reconstruction_triangles = 0;
  double ground_truth_area = 0.0, reconstruction_area = 0.0;  // m^2
  size_t free_space_cells = 0, reachable_cells = 0;
  SurfaceCloud ground_truth;  // normals turned to the side they are seen from
  SurfaceCloud reconstruction;
  std::vector<uint8_t> visible;  // per ground-truth sample
  CoverageResult coverage;
  std::vector<float> error;  // signed distance per ground-truth sample, NaN unless matched
  size_t matched = 0;        // covered samples with a distance
  ErrorStats error_stats;
  EvalTimings timings;

  size_t numVisible() const { return coverage.visible; }
  size_t numHidden() const { return ground_truth.size() - coverage.visible; }
};

class Evaluator {
 public:
  explicit Evaluator(const EvalConfig& config) : config_(config) {}

  // A bad config or an empty ground truth is an error; an empty
  // reconstruction is not (it covers nothing).
  Status evaluate(const TriangleMesh& ground_truth, const TriangleMesh& reconstruction, EvalResult* result) const;

  // The two halves of evaluate(), for scoring many reconstructions against
  // one ground truth (a mission's coverage over time): the ground-truth side
  // (samples, pruning, sensor bounds) into a fresh result, then the
  // reconstruction side (its samples, coverage, errors), replaced in a
  // result whose ground-truth side is prepared. Same figures as evaluate().
  Status prepareGroundTruth(const TriangleMesh& ground_truth, EvalResult* result) const;
  Status scoreReconstruction(const TriangleMesh& reconstruction, EvalResult* result) const;

 private:
  EvalConfig config_;
};

}  // namespace surface_nbv
