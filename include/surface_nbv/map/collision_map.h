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
// 0.3 m); a cell is an obstacle if any of its f^3 voxels is. A cell costs
// 30 bytes (DynamicEDT3D's 24-byte cell and bool, our state byte and a
// 4-byte query cache). Measured (bench_collision, 2 loaded cores): the power
// plant (72 x 50 x 17 m, 0.3 m voxels, f = 1) is 2.3M cells, 70 MB, built in
// 0.10 s all unknown and 0.16 s half known; the statue (28 x 28 x 64 m,
// 0.15 m voxels) with f = 2 is 1.9M cells, 57 MB, 0.05-0.11 s, but at 0.15 m
// it would be 14.9M cells, 450 MB, 0.6-0.8 s. Hence the 0.3 m default: a
// 0.3 m cell inflates obstacles by at most one voxel, small against the
// 1 m radius. An all-unknown map is cheap (obstacle cells whose neighbours
// are all obstacles enter the transform already settled); the cost is in
// clearing, paid incrementally as space is observed.
//
// Distance convention: for p, take the 8 cells whose centres surround p; the
// transform gives each the obstacle cell whose centre is nearest to its own
// centre. distance(p) is the Euclidean distance from p to the nearest of
// those obstacle cells taken as solid cubes (0 inside an obstacle cell), then
// the minimum with the distance to the bounds' faces (bounds_are_obstacle),
// capped at max_distance. It never under-estimates the distance from p to
// the union of obstacle cubes (each candidate is one of them), is exact when
// the nearest cube is among the candidates (always so for a single obstacle),
// and over-estimates by at most 0.51 cell elsewhere (worst of 4M random
// queries on random maps; test_collision_map asserts < 1 cell). With f > 1
// the cubes are whole cells, so it under-estimates the distance to the
// voxels by less than a cell.
//
// Thread safety: update() and rebuild() must not run concurrently with
// anything; between updates distance() and isFree() are const, read only a
// flat array and are safe to call from many threads. Units: metres, world
// frame (the TsdfMap's frame).
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
  // from. Removed blocks are not reported by the map: call rebuild() after
  // TsdfMap::clear() (update() notices it only while the map holds fewer
  // blocks than at the last update).
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
  // For every cell, whether cellCentreDistance(cell) >= clear (the same
  // test, read in one pass over the transform): mask[(x * ny + y) * nz + z]
  // is 1 or 0. Resizes *mask to the grid.
  void clearCells(double clear, std::vector<uint8_t>* mask) const;

  // What the last update() (or rebuild) did: blocks read, cells re-evaluated,
  // cells whose obstacle state changed. A rebuild counts every cell as changed.
  size_t lastBlocksVisited() const { return blocks_visited_; }
  // Unique in the process to each build of the transform from scratch (the
  // constructor, rebuild(), an update() that had to), over all collision
  // maps: an update changes distance() only within capCells() + 1 cells of
  // a cell whose obstacle state changed, a rebuild anywhere.
  uint64_t buildId() const { return build_id_; }
  int capCells() const { return cap_cells_; }
  size_t lastCellsEvaluated() const { return cells_evaluated_; }
  size_t lastCellsChanged() const { return cells_changed_; }
  // Bytes held by the transform, the cell states and the query cache.
  size_t memoryBytes() const;

  // Voxels per cell edge for a voxel size: the smallest multiple >= min_cell_size,
  // grown if needed so that max_distance spans at most kMaxCapCells cells.
  static int voxelsPerCellFor(double voxel_size, const CollisionConfig& config);
  static constexpr int kMaxCapCells = 127;

  // For tests: the query cache agrees with the transform in every cell.
  bool cacheMatchesTransform() const;

 private:
  class Edt;  // DynamicEDT3D with read access to its cells
  // The transform's nearest obstacle of a cell, as an offset from the cell
  // (|offset| < cap), so queries read 4 bytes from one flat array.
  struct Nearest {
    int8_t dx = 0, dy = 0, dz = 0;
    uint8_t valid = 0;
  };

  size_t linear(const Eigen::Vector3i& c) const {  // z fastest, as the transform stores it
    return static_cast<size_t>(c.z()) +
           static_cast<size_t>(grid_cells_.z()) *
               (static_cast<size_t>(c.y()) + static_cast<size_t>(grid_cells_.y()) * static_cast<size_t>(c.x()));
  }
  bool computeObstacle(const TsdfMap& map, const Eigen::Vector3i& cell) const;
  // Re-evaluates the cells covering a block; appends those whose state changed.
  void evaluateBlock(const TsdfMap& map, const Eigen::Vector3i& block, std::vector<Eigen::Vector3i>* changed);
  // Copies the transform into nearest_ over the cells lo..hi (inclusive, clamped).
  void syncNearest(const Eigen::Vector3i& lo, const Eigen::Vector3i& hi);
  Nearest nearestFromTransform(const Eigen::Vector3i& cell) const;

  CollisionConfig config_;
  Eigen::Vector3d origin_, bounds_max_;
  Eigen::Vector3i grid_voxels_, grid_cells_;
  int factor_ = 1;
  double cell_size_ = 0.0;
  int cap_cells_ = 0;                // the transform's cap in cells
  uint64_t build_id_ = 0;
  std::vector<uint8_t> obstacle_;    // per cell, what the transform holds
  std::vector<Nearest> nearest_;     // per cell, the transform's answer for queries
  std::unique_ptr<Edt> edt_;
  uint64_t last_stamp_ = 0;
  size_t seen_blocks_ = 0;
  size_t blocks_visited_ = 0, cells_evaluated_ = 0, cells_changed_ = 0;
};

}  // namespace surface_nbv
