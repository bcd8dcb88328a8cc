// Parameters of the evaluation against ground truth (docs/method.md, "Evaluation
// protocol"). Lengths in metres, angles in degrees. A zero length marked
// "0 = ..." selects a default tied to the voxel size; the accessors resolve it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "surface_nbv/common.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct EvalConfig {
  double voxel_size = 0.3;       // rho_v of the reconstruction: e_max = rho_v sqrt(3) / 2
  double point_spacing = 0.0;    // mean sample spacing (density 1 / spacing^2); 0 = voxel_size / 3
  size_t max_points = 20000000;  // per cloud; a finer spacing is refused
  uint64_t seed = 1;             // the same mesh, spacing and seed give the same samples
  int threads = 1;               // results repeat exactly whatever the count

  // Visibility pruning of the ground truth: a sample is kept when a sensor
  // position in reachable free space sees it within range.
  bool prune_hidden = true;
  // Where the sensor may be; empty = the ground truth's bounds grown by
  // bounds_margin, except below (the floor).
  AlignedBox bounds;
  double bounds_margin = 3.0;
  double min_range = 1.6;  // sensor range (Table 1 of the paper)
  double max_range = 8.0;
  double collision_radius = 1.0;    // sensor positions keep this far from the surface
  double free_space_cell = 0.5;     // cell size of the reachable free-space grid
  double max_incidence_deg = 80.0;  // largest angle between a line of sight and the normal
  int visibility_rays = 32;         // candidate lines of sight per side of the surface

  // M3C2-like signed distance along the ground-truth normal.
  double projection_radius = 0.0;      // cylinder radius; 0 = max(voxel_size / 2, 1.5 spacing)
  double max_depth = 0.0;              // cylinder half length along the normal; 0 = e_max
  double normal_radius = 0.0;          // 0 = triangle normals; > 0 = PCA normals at that scale
  double normal_agreement_deg = 45.0;  // neighbours whose normal is further from +-n are ignored
  int min_neighbours = 1;              // per cloud and cylinder, else no distance

  double eMax() const;
  double spacing() const;
  double projectionRadius() const;
  double maxDepth() const;
  // The bounds used for a ground truth with the given bounds.
  AlignedBox sensorBounds(const AlignedBox& ground_truth_bounds) const;
  // Names the first bad key, e.g. "point_spacing expected >= 0 (0 = voxel_size / 3)".
  Status validate() const;
};

}  // namespace surface_nbv
