// Marching Cubes over a TsdfMap (docs/method.md, "TSDF map": the surface is the
// zero level set of phi). The samples are voxel centres; the cube whose lowest
// corner is voxel v belongs to v's block and is meshed only when all 8 of its
// corners are known (w >= w_th; with TsdfConfig::mesh_min_weight >= 0, when
// all 8 have w > mesh_min_weight). Vertices are linearly interpolated along cube
// edges and triangles are wound counter-clockwise seen from positive phi, so
// their normals point into free space.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// Orders block indices by z, then y, then x.
struct BlockIndexLess {
  bool operator()(const Eigen::Vector3i& a, const Eigen::Vector3i& b) const {
    return std::make_tuple(a.z(), a.y(), a.x()) < std::make_tuple(b.z(), b.y(), b.x());
  }
};

// The triangles of the cubes one block owns, in world coordinates.
struct BlockMesh {
  Eigen::Vector3i block = Eigen::Vector3i::Zero();
  TriangleMesh mesh;
  // Per vertex: the voxel lattice edge it lies on (lower voxel and axis), the
  // same in every block, so vertices on block faces merge exactly.
  std::vector<uint64_t> edge_keys;
};

// Keeps one mesh per block of one TsdfMap. update() re-meshes only the blocks
// whose cubes read a block changed (or freed) since the previous update: a
// change in block B re-meshes B and its lower neighbours B - d, d in {0,1}^3
// (up to 8 blocks). The first update meshes everything. Not thread safe; to
// follow another map, call reset() first.
class MeshExtractor {
 public:
  using BlockMeshes = std::map<Eigen::Vector3i, BlockMesh, BlockIndexLess>;

  // Returns how many blocks were re-meshed or dropped (see lastUpdatedBlocks).
  size_t update(const TsdfMap& map);
  // Forgets every mesh; the next update meshes the whole map.
  void reset();

  // All block meshes in block order. With merge_vertices, vertices shared by
  // neighbouring cubes of different blocks become one (they are already
  // shared inside a block), giving a connected indexed mesh.
  TriangleMesh mesh(bool merge_vertices = true) const;
  // Non-empty block meshes, keyed by block index.
  const BlockMeshes& blockMeshes() const { return meshes_; }
  // Blocks re-meshed (or whose mesh was dropped) by the last update, sorted.
  const std::vector<Eigen::Vector3i>& lastUpdatedBlocks() const { return updated_; }

  // Meshes the cubes of one block from scratch (what update() does per block).
  static BlockMesh meshBlock(const TsdfMap& map, const Eigen::Vector3i& block);

 private:
  BlockMeshes meshes_;
  std::set<Eigen::Vector3i, BlockIndexLess> seen_;  // allocated blocks at the last update
  std::vector<Eigen::Vector3i> updated_;
  Eigen::Vector3i grid_blocks_ = Eigen::Vector3i::Zero();
  uint64_t last_counter_ = 0;
  bool full_ = true;
};

}  // namespace surface_nbv
