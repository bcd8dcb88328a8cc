// What the incomplete-surface stage hands to the planner (and the node): the
// ISE set C with C_rem marked, the merged viewpoints with their visible ISE
// sets C_q, the clusters with their gains (eq. 3), and how long each stage
// took. Plain data: indices refer into the vectors of the same Frontier.
// World frame, metres, radians.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "surface_nbv/common.h"
#include "surface_nbv/sensor/depth_camera.h"

namespace surface_nbv {

// One incomplete surface element (eq. 1).
struct Ise {
  uint64_t id = 0;                                   // linear voxel index (x fastest): stable for the voxel
  Eigen::Vector3i voxel = Eigen::Vector3i::Zero();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();   // voxel centre
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // n_v of eq. 2, unit; zero when the sum vanishes
  int32_t viewpoint = -1;   // merged viewpoint its own pose went into; -1 when in C_rem
  bool remaining = false;   // in C_rem: no acceptable pose (eq. 2 or fall-back)
  // In C_rem, and some candidate pose lay in unknown space: it may leave
  // C_rem once that space is observed (C_rem is recomputed every update).
  bool unknown_blocked = false;
  // Outside C_rem only through an approach pose (SurfaceConfig): its
  // viewpoint counts it as visible, since flying there is how it gets seen.
  bool approach = false;
};

// A 4-DOF configuration [x, y, z, yaw]: the camera at `position` on a level
// UAV, looking along `yaw` (0 = +x, counter-clockwise about +z), pitched down
// by the camera's mount pitch (CameraConfig::pitch_deg).
struct Viewpoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double yaw = 0.0;
  Eigen::Vector3d view_direction = Eigen::Vector3d::UnitX();  // unit, mean of pose -> ISE directions
  std::vector<uint32_t> sources;   // ISEs whose poses merged into this one, ascending
  std::vector<uint32_t> visible;   // C_q: ISEs seen from here, ascending
  int32_t cluster = -1;
  // Of the voxels rays across the frustum (to max range, each up to the
  // first occupied voxel) enter, the share that is unknown: how much unseen
  // space the viewpoint faces. 1 when not evaluated.
  double unknown_fraction = 1.0;

  // T_W_C of the optical frame (z forward, x right, y down) of `camera`'s mount.
  Transform cameraPose(const CameraConfig& camera) const;
};

struct Cluster {
  std::vector<uint32_t> viewpoints;  // ascending
  size_t visible_ises = 0;           // |union of C_q over its viewpoints|
  double gain = 0.0;                 // eq. 3: visible_ises / |C|
};

struct FrontierStats {
  // Wall-clock milliseconds per stage, and the whole update.
  double ise_ms = 0.0, viewpoints_ms = 0.0, merge_ms = 0.0, visibility_ms = 0.0, clusters_ms = 0.0, total_ms = 0.0;
  bool full_extraction = false;   // C was re-extracted from scratch
  size_t blocks_changed = 0;      // map blocks re-read
  size_t blocks_examined = 0;     // blocks whose ISEs were recomputed
  size_t poses_tested = 0;        // candidate poses over all ISEs
  size_t fallback_poses = 0;      // ISEs whose pose is a fall-back, not the eq. 2 pose
  size_t unmerged_viewpoints = 0; // one per ISE outside C_rem
  size_t approach_poses = 0;      // ISEs whose pose is an approach pose
  size_t poses_reused = 0;        // ISEs whose n_v and pose search were kept from the last update
  size_t views_reused = 0;        // viewpoints whose C_q and unknown_fraction were kept from the last update
  uint64_t voxel_steps = 0;       // DDA steps of the visibility stage
  size_t links = 0;               // cluster-graph edges

  double voxelStepsPerSecond() const { return visibility_ms > 0.0 ? voxel_steps / (visibility_ms * 1e-3) : 0.0; }
};

struct Frontier {
  std::vector<Ise> ises;            // C, by block slot then voxel within the block
  size_t remaining = 0;             // |C_rem|
  size_t remaining_unknown = 0;     // ISEs of C_rem with unknown_blocked
  size_t scanned = 0;               // scanned elements (see IseExtractor)
  std::vector<Viewpoint> viewpoints;
  std::vector<Cluster> clusters;    // by smallest viewpoint index
  uint64_t map_stamp = 0;           // the map's change counter this frontier reflects
  FrontierStats stats;

  size_t insideCount() const { return ises.size() - remaining; }  // |C_ins|
  // The mission is complete when no ISE outside C_rem remains.
  bool complete() const { return insideCount() == 0; }
};

}  // namespace surface_nbv
