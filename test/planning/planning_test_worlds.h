// Small known maps for the planning tests: free space with walls, obstacles
// that appear later, all with exact collision maps (cell = voxel); and the
// seeded planner configuration the tests plan with.
#pragma once

#include <cmath>
#include <memory>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/planning/path_planner.h"

namespace surface_nbv {

// 12 x 12 x 5 m of known free space, 0.25 m voxels, with a wall across x = 0
// (voxel columns x in [-0.25, 0.25)) that leaves a gap for y >= 1 m when open.
class WallWorld {
 public:
  explicit WallWorld(bool gap) : map_(config()) {
    const Eigen::Vector3i& g = map_.gridVoxels();
    for (int z = 0; z < g.z(); ++z)
      for (int y = 0; y < g.y(); ++y)
        for (int x = 0; x < g.x(); ++x) set(Eigen::Vector3i(x, y, z), inWall(Eigen::Vector3i(x, y, z), gap));
    CollisionConfig cc;
    cc.min_cell_size = 0.0;
    collision_ = std::make_unique<CollisionMap>(map_, cc);
  }
  // Fills the gap and updates the collision map.
  void closeGap() {
    const Eigen::Vector3i& g = map_.gridVoxels();
    for (int z = 0; z < g.z(); ++z)
      for (int y = 0; y < g.y(); ++y)
        for (int x = 0; x < g.x(); ++x)
          if (inWall(Eigen::Vector3i(x, y, z), false)) set(Eigen::Vector3i(x, y, z), true);
    collision_->update(map_);
  }
  // Empties the gap again and updates the collision map.
  void openGap() {
    const Eigen::Vector3i& g = map_.gridVoxels();
    for (int z = 0; z < g.z(); ++z)
      for (int y = 0; y < g.y(); ++y)
        for (int x = 0; x < g.x(); ++x) {
          const Eigen::Vector3i v(x, y, z);
          if (inWall(v, false) && !inWall(v, true)) set(v, false);
        }
    collision_->update(map_);
  }
  // Makes the box [lo, hi] occupied and updates the collision map.
  void addBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    const Eigen::Vector3i& g = map_.gridVoxels();
    for (int z = 0; z < g.z(); ++z)
      for (int y = 0; y < g.y(); ++y)
        for (int x = 0; x < g.x(); ++x) {
          const Eigen::Vector3d p = map_.voxelCenter(Eigen::Vector3i(x, y, z));
          if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) set(Eigen::Vector3i(x, y, z), true);
        }
    collision_->update(map_);
  }
  const CollisionMap& collision() const { return *collision_; }
  const TsdfMap& map() const { return map_; }
  AlignedBox bounds() const { return config().bounds; }

 private:
  static TsdfConfig config() {
    TsdfConfig c;
    c.voxel_size = 0.25;
    c.bounds = AlignedBox(Eigen::Vector3d(-6, -6, 0), Eigen::Vector3d(6, 6, 5));
    return c;
  }
  bool inWall(const Eigen::Vector3i& v, bool gap) const {
    const Eigen::Vector3d p = map_.voxelCenter(v);
    return std::abs(p.x()) < 0.25 && !(gap && p.y() >= 1.0);
  }
  void set(const Eigen::Vector3i& v, bool occupied) {
    TsdfVoxel* voxel = map_.allocateVoxel(v);
    voxel->w = 1.0f;
    voxel->phi = occupied ? -0.1f : 0.2f;
    map_.mutableBlock(TsdfMap::blockOfVoxel(v))->change_stamp = map_.beginChange();
  }

  TsdfMap map_;
  std::unique_ptr<CollisionMap> collision_;
};

// A planner with sampler seed `seed` whose plan() stops after `iterations`
// roadmap samples, so that its paths repeat on any machine; `time_budget`
// (wall seconds) only guards against a slow machine.
inline PathPlannerConfig seededPlannerConfig(unsigned int seed, int iterations, double time_budget) {
  PathPlannerConfig c;
  c.seed = seed;
  c.iteration_budget = iterations;
  c.time_budget = time_budget;
  return c;
}

}  // namespace surface_nbv
