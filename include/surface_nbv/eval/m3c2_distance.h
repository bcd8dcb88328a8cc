// M3C2-like signed distance (after Lague et al. 2013, as CloudCompare's M3C2
// the paper used) from reference samples (ground truth) to a compared cloud
// (reconstruction). At a core point p with unit axis n, each cloud's points
// inside the cylinder of radius projection_radius and half length max_depth
// along n are projected on n, keeping those whose normal lies within
// normal_agreement_deg of +n or of -n; where both kinds are there (the two
// faces of a thin plate, or a mesh wound both ways) the kind whose mean lies
// nearer to p stands for the surface. The distance is the compared cloud's
// mean projection minus the reference's: positive when the reconstruction
// lies on the side n points to. The axis is the sample's normal, or with
// normal_radius > 0 the PCA normal of the reference at that scale, turned to
// agree with it. Const and thread safe.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "surface_nbv/eval/eval_config.h"
#include "surface_nbv/eval/point_index.h"
#include "surface_nbv/eval/surface_sampler.h"

namespace surface_nbv {

class M3c2Distance {
 public:
  explicit M3c2Distance(const EvalConfig& config);

  // Distances at the reference samples with core[i] != 0, NaN elsewhere and
  // where a cylinder holds fewer than min_neighbours points. Indexes may hold
  // a subset of their cloud (e.g. the visible ground truth only).
  std::vector<float> compute(const SurfaceCloud& reference, const PointIndex& reference_index,
                             const SurfaceCloud& compared, const PointIndex& compared_index,
                             const std::vector<uint8_t>& core) const;

  // The distance at one core point p with unit axis n.
  float at(const Eigen::Vector3f& p, const Eigen::Vector3f& n, const SurfaceCloud& reference,
           const PointIndex& reference_index, const SurfaceCloud& compared, const PointIndex& compared_index) const;

 private:
  // Mean projection on n of the cloud's surface in the cylinder; NaN if too few points.
  double meanProjection(const Eigen::Vector3f& p, const Eigen::Vector3f& n, const SurfaceCloud& cloud,
                        const PointIndex& index) const;

  EvalConfig config_;
  double radius_, depth_, search_radius_, cos_agreement_;
};

}  // namespace surface_nbv
