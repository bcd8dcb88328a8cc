// Gaze while flying: the yaw along a leg that keeps the most incomplete
// surface in the camera's view, so the UAV scans ISEs it passes instead of
// looking down the corridor it flies through.
//
// The camera at p with yaw psi (on a level UAV, pitched down by its mount's
// CameraConfig::pitch_deg) sees an ISE v when the depth of v on
// the optical axis is in [min_range, max_range], v lies inside the
// horizontal and vertical FOV, p is on the free side of v (the ISE's
// direction n_v of eq. 2 points towards p) and the segment from p to v stays
// out of obstacle cells of the collision map (unknown space blocks, as for
// C_q) up to `end_margin` before v (v's own neighbours are unknown or
// occupied). The leg is resampled every `step` metres; each new vertex looks
// at the yaw (of `yaw_bins` evenly spaced) that sees the most ISEs, when that
// is at least `min_ises`, else along the leg. Ties go to the yaw closest to
// the direction of travel. Vertices within `keep_end` of the leg's end keep
// their yaw (the turn to the target's).
//
// Deterministic, no state; cost per vertex: the ISEs within max_range, each
// a facing test and a walk of the segment at half-cell steps.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

class CollisionMap;

struct GazeConfig {
  bool enabled = false;
  double step = 2.0;        // m between resampled vertices
  int min_ises = 3;         // fewer visible ISEs: look along the leg
  int yaw_bins = 36;        // candidate yaws over the full turn
  double end_margin = 0.5;  // m before the ISE where the line-of-sight walk stops
  // Its FOV and ranges (nbv_mission and nbv_planner copy nbv/camera).
  CameraConfig camera;

  Status validate() const;
};

// The ISEs of C_ins (not remaining) with a direction, as gaze targets.
struct GazeTarget {
  Eigen::Vector3d position, direction;
};
std::vector<GazeTarget> gazeTargets(const Frontier& frontier);

// How many targets the camera at `p` with `yaw` sees (see above).
int countVisible(const GazeConfig& config, const std::vector<GazeTarget>& targets, const CollisionMap* map,
                 const Eigen::Vector3d& p, double yaw);

// Rewrites the yaws of `path` (x, y, z, yaw; yaws along the leg already set)
// with resampled vertices, keeping the first vertex and the last keep_end
// metres as they are. Returns the number of vertices whose yaw the gaze set.
int applyGaze(const GazeConfig& config, const std::vector<GazeTarget>& targets, const CollisionMap* map,
              double keep_end, std::vector<Eigen::Vector4d>* path);

}  // namespace surface_nbv
