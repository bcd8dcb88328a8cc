// Distance to the nearest obstacle for the planner's collision checks, kept
// up to date from a TsdfMap by an incremental Euclidean distance transform
// (dynamicEDT3D, Lau et al.).
//
// Obstacles: occupied voxels, unknown voxels when unknown_is_obstacle (voxels
// of unallocated blocks are unknown), and, when bounds_are_obstacle, all
// space outside the map's bounds.
//
// Resolution: the transform runs on collision cells, each the smallest
// integer multiple f of the TSDF voxel that is >= min_cell_size (default
// 0.3 m); a cell is an obstacle if any of its f^3 voxels is. DynamicEDT3D
// costs ~26 bytes per cell (a 24-byte dataCell, its bool grid and our state
// byte), so 0.15 m voxels over the statue bounds (28 x 28 x 64 m = 187 x 187
// x 427 = 14.9M cells) would need ~390 MB and about 1-2 s to build, against
// 1.9M cells (~50 MB, 0.2 s) at 0.3 m; the power plant (72 x 50 x 17 m at
// 0.3 m, f = 1) is 2.3M cells (~60 MB). A 0.3 m cell against a 1 m radius
// keeps the passages the planner needs; figures from bench/bench_collision.
//
// Distance convention: the transform gives, for the cell c containing p, the
// obstacle cell o whose centre is nearest to c's centre; distance(p) is the
// Euclidean distance from p to the cube of o (0 inside an obstacle cell),
// then the minimum with the distance to the bounds' faces, capped at
// max_distance. It never under-estimates the distance from p to the union of
// obstacle cubes (o is one of them), is exact when o is also the cube nearest
// to p (always so for a single obstacle), and over-estimates by less than one
// cell elsewhere (measured on random maps in test_collision_map; the proven
// bound is 2.1 cells). With f > 1 obstacles are inflated to whole cells.
//
// Thread safety: update()/rebuild() must not run concurrently with anything;
// between updates distance() and isFree() are const and safe to call from
// many threads. Units: metres, world frame (the TsdfMap's frame).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct CollisionConfig {
  double max_distance = 2.0;       // cap on distance() [m]; >= 2 m (twice the paper's 1 m radius)
  bool unknown_is_obstacle = true;
  bool bounds_are_obstacle = true; // outside the bounds counts as an obstacle for the distance too
  double min_cell_size = 0.3;      // collision cell >= this, an integer multiple of the voxel [m]; 0 = voxel

  // Names the first bad key, e.g. "max_distance expected >= 2.0".
  Status validate() const;
};

class CollisionMap {
 public:
  // Builds from scratch from `map`. `config` must validate(); the constructor trusts it.
  CollisionMap(const TsdfMap& map, const CollisionConfig& config);
  ~CollisionMap();
  CollisionMap(const CollisionMap&) = delete;
  CollisionMap& operator=(const CollisionMap&) = delete;

  // Applies the blocks of `map` changed since the last update or rebuild:
  // recomputes only the cells those blocks cover, passes only the cells whose
  // state changed to the transform. `map` must be the map this was built
  // from; after TsdfMap::clear() (noticed as fewer blocks) it rebuilds.
  void update(const TsdfMap& map);
  // Recomputes every cell and the whole transform.
  void rebuild(const TsdfMap& map);

  // Metres to the nearest obstacle (see the convention above), in
  // [0, max_distance]; 0 outside the bounds and for non-finite p.
  double distance(const Eigen::Vector3d& p_W) const;
  // True iff a ball of `radius` around p_W holds no obstacle:
  // distance(p_W) > radius. False when radius >= max_distance (the cap
  // cannot certify it).
  bool isFree(const Eigen::Vector3d& p_W, double radius) const;

  // Cell grid: cell (i, j, k) covers bounds.min + cellSize() * [i, i+1) (and so on).
  double cellSize() const { return cell_size_; }
  int voxelsPerCell() const { return factor_; }
  const Eigen::Vector3i& gridCells() const { return grid_cells_; }
  bool isObstacleCell(const Eigen::Vector3i& cell) const;
  // Distance between the centres of `cell` and its nearest obstacle cell [m],
  // as the transform holds it; saturates a little above max_distance.
  double cellCentreDistance(const Eigen::Vector3i& cell) const;

  // What the last update() (or rebuild) did: blocks read, cells re-evaluated,
  // cells whose obstacle state changed. A rebuild counts every cell as changed.
  size_t lastBlocksVisited() const { return blocks_visited_; }
  size_t lastCellsEvaluated() const { return cells_evaluated_; }
  size_t lastCellsChanged() const { return cells_changed_; }
  // Bytes held by the transform and the cell states.
  size_t memoryBytes() const;

  // The collision cell size for a voxel size: the smallest multiple >= min_cell_size.
  static int voxelsPerCellFor(double voxel_size, const CollisionConfig& config);

 private:
  class Edt;  // DynamicEDT3D with read access to its cells

  size_t linear(const Eigen::Vector3i& c) const {
    return static_cast<size_t>(c.x()) +
           static_cast<size_t>(grid_cells_.x()) *
               (static_cast<size_t>(c.y()) + static_cast<size_t>(grid_cells_.y()) * static_cast<size_t>(c.z()));
  }
  bool computeObstacle(const TsdfMap& map, const Eigen::Vector3i& cell) const;
  // Re-evaluates the cells covering a block; appends those whose state changed.
  void evaluateBlock(const TsdfMap& map, const Eigen::Vector3i& block, std::vector<Eigen::Vector3i>* changed);

  CollisionConfig config_;
  Eigen::Vector3d origin_, bounds_max_;
  Eigen::Vector3i grid_voxels_, grid_cells_;
  int factor_ = 1;
  double cell_size_ = 0.0;
  int max_sq_cells_ = 0;             // the transform's cap, squared cells
  std::vector<uint8_t> obstacle_;    // per cell, what the transform holds
  std::unique_ptr<Edt> edt_;
  uint64_t last_stamp_ = 0;
  size_t seen_blocks_ = 0;
  size_t blocks_visited_ = 0, cells_evaluated_ = 0, cells_changed_ = 0;
};

}  // namespace surface_nbv
