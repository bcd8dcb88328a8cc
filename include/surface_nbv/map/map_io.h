// Saving and loading a TsdfMap in a versioned little-endian binary file:
//   "SNBVTSDF", uint32 version (1), double voxel_size, uint32 block_size (8),
//   float w_th, double truncation, 3 x double bounds min, 3 x double bounds max,
//   uint64 number of blocks, then per block 3 x int32 index and 512 x
//   (float phi, float w) in TsdfBlock::linear order, then uint32 CRC-32 (zlib)
//   of every byte before it. Change stamps are not stored.
#pragma once

#include <cstdint>
#include <string>

#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

constexpr uint32_t kMapFormatVersion = 1;

// Writes the allocated blocks (sorted by index) to `path` + ".tmp", fsyncs it,
// then renames it onto `path` (and fsyncs the directory), so a crash leaves
// either the previous file or the new one, never a torn file. On failure the
// ".tmp" is removed and `path` is untouched.
Status saveMap(const TsdfMap& map, const std::string& path);

// Replaces the blocks of `map` by those of the file. The file must be a
// complete, checksum-valid version-1 map whose voxel size equals the map's
// (relative 1e-9), whose block size is kBlockSize, whose bounds min equals
// the map's (within 1e-6 voxel, so block indices mean the same place), and
// whose blocks all lie inside the map's block grid and fit its max_blocks.
// w_th, truncation and bounds max of the file may differ (the map's config
// wins). Voxels must be finite with w >= 0 and no block may repeat. On any
// error the message names the file and the fault, and `map` is unchanged; on
// success every loaded block carries a fresh change stamp.
Status loadMap(const std::string& path, TsdfMap* map);

}  // namespace surface_nbv
