// Parameters of the incomplete-surface stage (docs/method.md, "ISE", "Viewpoint
// for an ISE", "Clusters"): viewpoint distance and fall-backs, merging,
// visibility and clustering. Lengths in metres, angles in degrees. W_th and
// the bounds come from the TsdfMap, the collision model from the CollisionMap.
#pragma once

#include <vector>

#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct SurfaceConfig {
  // Eq. 2: a viewpoint sits delta_pose from its ISE along n_v (Table 1: 4.7 m
  // for the plant, 3.6 m for the statue).
  double delta_pose = 4.7;
  // Fall-backs when that pose is not acceptable, tried in order: n_v turned
  // by +-a in yaw, then in elevation, for each a here; along each direction,
  // delta_pose times each fraction here, then the distance at which the ISE
  // sits at the camera's min range.
  std::vector<double> fallback_rotations_deg{30.0, 60.0, 90.0};
  std::vector<double> fallback_distance_fractions{0.75, 0.5};
  // Approach poses for ISEs whose every candidate failed and some lay in
  // unknown space: the same directions again, at the usual distances and
  // farther out up to this fraction of the camera's max range, accepting a
  // line of sight through unknown (never occupied) voxels. Flying there
  // observes the unknown space in between, so the ISE is not left in C_rem
  // before anyone looked. 0 turns approach poses off.
  double approach_range_fraction = 0.0;
  // Evaluate Viewpoint::unknown_fraction (54 rays per viewpoint).
  bool unknown_fraction = true;
  // The ISE of a viewpoint must lie this far inside the vertical FOV edges
  // (the UAV cannot pitch).
  double fov_margin_deg = 2.0;
  // Clearance of a viewpoint and of a cluster link [m] (1 m in the paper).
  double collision_radius = 1.0;

  // Merging: viewpoints whose positions are closer than epsilon, or closer
  // than parallel_distance with viewing directions whose dot product is at
  // least parallel_cos, become one (mean position, mean orientation).
  double epsilon = 1.2;              // about delta_pose / 4
  double parallel_distance = 2.4;
  double parallel_cos = 0.985;       // about 10 degrees

  // Visibility: rays stop at occupied voxels, and at unknown ones when this
  // is true (the default: an unknown voxel may hide a surface, and the
  // collision model treats unknown space as an obstacle too, so a gain counts
  // only ISEs whose line of sight is known to be clear).
  bool unknown_blocks_visibility = true;
  CameraConfig camera;

  // Clusters: q_i and q_j are neighbours when a collision-free straight
  // segment shorter than d_nu joins them; a viewpoint with no neighbour
  // widens its own search by d_nu_step up to d_nu_max (Table 1: 2 and 5 m).
  double d_nu = 2.0;
  double d_nu_max = 5.0;
  double d_nu_step = 0.5;

  int threads = 1;

  // Names the first bad key, e.g. "delta_pose expected > 0".
  Status validate() const;
};

}  // namespace surface_nbv
