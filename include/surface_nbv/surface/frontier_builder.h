// Runs the whole incomplete-surface stage on a TsdfMap and its CollisionMap:
// ISEs (incremental, IseExtractor), one pose per ISE (eq. 2 with fall-backs,
// ViewpointGenerator; ISEs without one form C_rem), merging
// (ViewpointMerger), visibility C_q (VisibilityEvaluator) and clusters with
// gains (ViewpointClusterer), timing each stage. Stages after the ISEs are
// recomputed on every update, except one ISE's n_v and pose search: those
// read the voxel states within ViewpointGenerator::maxDistance() of it and
// the collision distance at the candidates, which an update changes only
// within the transform's cap (CollisionMap::capCells) of a cell whose
// obstacle state changed. An ISE farther than both from every block whose
// voxel states changed (IseExtractor::changedStateBlocks), on the same
// collision map build (CollisionMap::buildId), keeps the last update's n_v and
// search. Likewise a merged viewpoint at the same position and yaw as one of
// the last update, farther than max_range and two voxels from every such
// block, keeps its C_q (as ISE ids), its DDA steps and unknown_fraction:
// what it sees and the ISEs it could see are the same. Both give the answer
// of searching again (test_frontier_builder checks them against a builder
// that searches every time). Single-threaded use; the stages run on
// config.threads threads and give the same Frontier for any count.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/surface/ise_extractor.h"
#include "surface_nbv/surface/surface_config.h"
#include "surface_nbv/surface/viewpoint_clusterer.h"
#include "surface_nbv/surface/viewpoint_generator.h"
#include "surface_nbv/surface/viewpoint_merger.h"
#include "surface_nbv/surface/visibility_evaluator.h"
#include "surface_nbv/surface/voxel_ray_caster.h"
#include "surface_nbv/util/bits_hash.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// Viewpoint::unknown_fraction: 9 x 6 rays across the camera's frustum from
// the viewpoint to max range, each walked up to its first occupied voxel
// (`rays` must not be blocked by unknown voxels); the share of the voxels
// entered that are unknown. 1 when no ray enters a voxel (e.g. outside the grid).
double unknownFraction(const VoxelRayCaster& rays, const Viewpoint& viewpoint, const CameraConfig& camera);

class FrontierBuilder {
 public:
  // `config` must validate(); the constructor trusts it.
  explicit FrontierBuilder(const SurfaceConfig& config);

  // Brings the ISEs up to date with the blocks of `map` changed since the
  // last update, then recomputes everything else into *frontier. `collision`
  // must be built from `map` and up to date with it, with a max_distance
  // above config.collision_radius. Error (frontier untouched) when the
  // collision map's grid does not cover the map's.
  Status update(const TsdfMap& map, const CollisionMap& collision, Frontier* frontier);
  // The next update re-extracts every ISE and searches every pose.
  void reset() {
    extractor_ = IseExtractor(config_.threads);
    poses_.clear();
    views_.clear();
  }
  // Off: every update searches every ISE's pose and evaluates every
  // viewpoint (the reference the kept ones are tested against).
  void setReusePoses(bool on) { reuse_poses_ = on; }

  const IseExtractor& extractor() const { return extractor_; }
  const SurfaceConfig& config() const { return config_; }

 private:
  SurfaceConfig config_;
  IseExtractor extractor_;
  ViewpointGenerator generator_;
  ViewpointMerger merger_;
  VisibilityEvaluator visibility_;
  ViewpointClusterer clusterer_;

  // An ISE's n_v and pose search as of the last update, by ISE id.
  struct KeptPose {
    Eigen::Vector3d direction;
    PoseSearch search;
    Viewpoint pose;
  };
  // A merged viewpoint's C_q (by ISE id), its DDA steps and unknown_fraction, by position and yaw.
  struct KeptView {
    std::vector<uint64_t> visible;
    uint64_t steps = 0;
    double unknown_fraction = 1.0;
  };
  using ViewKey = BitsKey<4>;
  using ViewKeyHash = BitsKeyHash<4>;
  static ViewKey keyOf(const Viewpoint& q);
  // Per block slot: within `reach` metres (max norm) of a voxel whose state
  // changed in the last extraction, as far as blocks tell (a superset).
  std::vector<uint8_t> nearChanges(double reach, double voxel_size) const;
  // n_v and pose searches into out->ises and `poses` (kept or searched).
  void searchPoses(const TsdfMap& map, const CollisionMap& collision, bool keep, const VoxelRayCaster& rays,
                   const VoxelRayCaster* approach, std::vector<Viewpoint>* poses, std::vector<PoseSearch>* searches,
                   Frontier* out);
  // C_q and unknown_fraction of every viewpoint of *out (kept or evaluated).
  void evaluateViews(bool keep, double voxel_size, const VoxelRayCaster& rays, const VoxelRayCaster& loose,
                     Frontier* out);
  bool reuse_poses_ = true;
  std::unordered_map<uint64_t, KeptPose> poses_;
  std::unordered_map<ViewKey, KeptView, ViewKeyHash> views_;
  uint64_t kept_build_ = 0;  // CollisionMap::buildId() the kept poses were searched on
};

}  // namespace surface_nbv
