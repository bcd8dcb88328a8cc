// An offline oracle for the exploration path (issue #8): it knows the ground-
// truth mesh, so it can pick viewpoints that together see the visible surface
// and fly them in a short order. The online planner's path length and flight
// time are reported as ratios to the oracle's.
//
//   1. targets: area-uniform samples of the mesh (SurfaceSampler),
//   2. a perfect-knowledge TsdfMap (voxels within half a voxel diagonal of a
//      triangle occupied, every other voxel in the bounds known free) and its
//      CollisionMap,
//   3. candidates: surface samples offset by fractions of delta_pose along
//      +n and -n (elevation clamped into the vertical FOV: 4-DOF UAV, level
//      camera; a pose in collision is retried at the FOV's upper, then lower
//      edge), facing the sample; kept when isFree(p, radius + cell) and
//      reachable from the start (ReachableSpace: a flood fill over the
//      collision cells whose centre passes the path planner's isFree test),
//   4. visibility: each candidate's depth image (DepthRenderer, Embree) sees
//      a target that projects inside it, within range, at the rendered depth
//      (within depth_tolerance_voxels) and under max_incidence_deg,
//   5. greedy set cover until cover_fraction of the coverable targets (those
//      some candidate sees) are seen, or no candidate adds any,
//   6. tour: open-path Lin-Kernighan over straight-line costs from the start,
//      then PathPlanner (LazyPRM*, iteration budget) legs in that order; the
//      flight time is timeWaypoints() at the speed and yaw rate.
// Same config, mesh and seed: same result. Units: metres, seconds, radians,
// world frame. Not thread safe; plan() uses `threads` threads inside.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/mission/mission_config.h"
#include "surface_nbv/planning/path_planner.h"
#include "surface_nbv/planning/tour_result.h"
#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/sim/raycast_scene.h"
#include "surface_nbv/tracking/trajectory.h"

namespace surface_nbv {

struct OracleConfig {
  CameraConfig camera;
  TsdfConfig tsdf;              // bounds, voxel size, w_th of the perfect map
  CollisionConfig collision;
  PathPlannerConfig path;       // collision_radius, seed; budgets set below
  Eigen::Vector4d start{0.0, 0.0, 2.0, 0.0};  // [x, y, z, yaw]
  double delta_pose = 4.7;                     // viewpoint distance (Table 1)
  std::vector<double> offset_fractions{1.0, 0.75, 0.5};  // of delta_pose, each in (0, 2]
  double target_spacing = 0.5;     // target sample spacing [m]
  double candidate_spacing = 1.0;  // spacing of the samples candidates are built from [m]
  size_t max_candidates = 20000;   // a seeded subset is kept above this
  size_t max_targets = 4000000;
  double depth_tolerance_voxels = 1.5;
  double max_incidence_deg = 80.0;
  double vfov_margin_deg = 5.0;    // candidates keep their sample this far inside the vertical FOV
  double cover_fraction = 0.99;    // of the coverable targets
  int path_iterations = 100;       // LazyPRM* samples per leg (repeatable; the roadmap persists)
  bool refine_paths = true;        // LazyPRM* shortens each leg for its whole budget (else first path)
  double path_time_limit = 60.0;   // safety wall-time per leg [s]
  double speed = 0.5;              // m/s
  double yaw_rate = 0.5;           // rad/s
  int threads = 2;
  unsigned int seed = 1;

  // Names the first bad key.
  Status validate() const;
};

// The oracle's parameters from a mission's (same camera, map, radius, start, delta_pose, speeds).
OracleConfig oracleConfigFrom(const MissionConfig& mission);

struct OracleTimes {  // wall-clock milliseconds per step
  double targets = 0, map = 0, candidates = 0, visibility = 0, cover = 0, tour = 0, paths = 0, total = 0;
};

struct OracleResult {
  Status status;  // an error means the oracle could not run
  size_t targets = 0, coverable = 0, covered = 0;  // covered counts coverable targets seen by the chosen set
  size_t candidates_built = 0, candidates = 0;     // before and after the collision / reachability filter
  std::vector<Eigen::Vector3d> uncoverable;        // targets no candidate sees
  std::vector<Eigen::Vector4d> viewpoints;         // chosen [x, y, z, yaw], in greedy order
  std::vector<size_t> gains;                       // new targets each chosen viewpoint added
  std::vector<int> order;                          // tour: indices into viewpoints, visiting order
  TspStatus tour_status = TspStatus::kInvalidInput;
  double tour_length = 0.0;                        // straight-line open path from the start [m]
  std::vector<Eigen::Vector4d> path;               // whole flown path, start first
  std::vector<int> path_viewpoint;                 // per path pose: viewpoint reached there, else -1
  size_t failed_legs = 0;                          // legs without a path (their viewpoint is skipped)
  double path_length = 0.0;                        // m
  Trajectory timed;                                // the path timed at speed and yaw_rate, from t = 0
  double flight_time = 0.0;                        // s, timed's duration
  OracleTimes times;

  double coveredFraction() const { return coverable ? double(covered) / coverable : 0.0; }
};

class OraclePlanner {
 public:
  // `config` must validate(); mesh and scene (the same mesh) must outlive the planner.
  OraclePlanner(const OracleConfig& config, const TriangleMesh& mesh, const RaycastScene& scene);
  ~OraclePlanner();

  // Called with a line of progress at each step.
  void setProgress(std::function<void(const std::string&)> progress) { progress_ = std::move(progress); }

  OracleResult plan();

  // The perfect map and its collision map after plan() (null before).
  const TsdfMap* map() const { return map_.get(); }
  const CollisionMap* collision() const { return collision_.get(); }

 private:
  struct Candidates;
  void say(const std::string& line) const;
  void buildMap();
  void buildCandidates(Candidates* c, OracleResult* r) const;
  std::vector<std::vector<uint32_t>> visibility(const Candidates& c, const std::vector<Eigen::Vector3d>& targets,
                                                const std::vector<Eigen::Vector3d>& normals) const;
  void tour(OracleResult* r);

  OracleConfig config_;
  const TriangleMesh& mesh_;
  const RaycastScene& scene_;
  std::unique_ptr<TsdfMap> map_;
  std::unique_ptr<CollisionMap> collision_;
  std::function<void(const std::string&)> progress_;
};

}  // namespace surface_nbv
