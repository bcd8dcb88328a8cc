// Runs the whole incomplete-surface stage on a TsdfMap and its CollisionMap:
// ISEs (incremental, IseExtractor), one pose per ISE (eq. 2 with fall-backs,
// ViewpointGenerator; ISEs without one form C_rem), merging
// (ViewpointMerger), visibility C_q (VisibilityEvaluator) and clusters with
// gains (ViewpointClusterer), timing each stage. Stages after the ISEs are
// recomputed on every update. Single-threaded use; the stages run on
// config.threads threads and give the same Frontier for any count.
#pragma once

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
  // The next update re-extracts every ISE.
  void reset() { extractor_ = IseExtractor(config_.threads); }

  const IseExtractor& extractor() const { return extractor_; }
  const SurfaceConfig& config() const { return config_; }

 private:
  SurfaceConfig config_;
  IseExtractor extractor_;
  ViewpointGenerator generator_;
  ViewpointMerger merger_;
  VisibilityEvaluator visibility_;
  ViewpointClusterer clusterer_;
};

}  // namespace surface_nbv
