// Hand-built maps for the surface tests: 0.25 m voxels (exact in binary),
// states written voxel by voxel, each write stamping its block as changed.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/surface/surface_config.h"
#include "surface_nbv/surface/voxel_state_grid.h"

namespace surface_nbv {
namespace test {

constexpr double kVoxel = 0.25;

// A map of n voxels per axis from the origin.
inline TsdfConfig gridConfig(const Eigen::Vector3i& n) {
  TsdfConfig c;
  c.voxel_size = kVoxel;
  c.bounds = AlignedBox(Eigen::Vector3d::Zero(), n.cast<double>() * kVoxel);
  return c;
}

inline void setState(TsdfMap* map, const Eigen::Vector3i& v, VoxelState state) {
  TsdfVoxel* voxel = map->allocateVoxel(v);
  ASSERT_NE(voxel, nullptr) << v.transpose();
  voxel->w = state == VoxelState::kUnknown ? 0.0f : 1.0f;
  voxel->phi = state == VoxelState::kOccupied ? -0.1f : 0.2f;
  map->mutableBlock(TsdfMap::blockOfVoxel(v))->change_stamp = map->beginChange();
}

// Voxels lo <= v < hi (per axis).
inline void fillBox(TsdfMap* map, const Eigen::Vector3i& lo, const Eigen::Vector3i& hi, VoxelState state) {
  for (int z = lo.z(); z < hi.z(); ++z)
    for (int y = lo.y(); y < hi.y(); ++y)
      for (int x = lo.x(); x < hi.x(); ++x) setState(map, Eigen::Vector3i(x, y, z), state);
}

inline void fillAll(TsdfMap* map, VoxelState state) {
  fillBox(map, Eigen::Vector3i::Zero(), map->gridVoxels(), state);
}

// Collision cells equal to the voxels, so distances are exact on these maps.
inline std::unique_ptr<CollisionMap> collisionFor(const TsdfMap& map) {
  CollisionConfig c;
  c.min_cell_size = 0.0;
  return std::make_unique<CollisionMap>(map, c);
}

// 12 x 12 x 6 m, all known free, with its collision map.
struct FreeMap {
  TsdfMap map{gridConfig(Eigen::Vector3i(48, 48, 24))};
  std::unique_ptr<CollisionMap> collision;
  FreeMap() {
    fillAll(&map, VoxelState::kFree);
    collision = collisionFor(map);
  }
};

inline SurfaceConfig testSurfaceConfig() {
  SurfaceConfig c;
  c.threads = 1;
  return c;
}

// A VoxelStateGrid of `map` with every block slot refreshed.
inline VoxelStateGrid gridOf(const TsdfMap& map) {
  VoxelStateGrid grid;
  grid.reset(map);
  const Eigen::Vector3i& b = map.gridBlocks();
  for (int z = 0; z < b.z(); ++z) {
    for (int y = 0; y < b.y(); ++y) {
      for (int x = 0; x < b.x(); ++x) grid.refreshBlock(map, Eigen::Vector3i(x, y, z));
    }
  }
  return grid;
}

}  // namespace test
}  // namespace surface_nbv
