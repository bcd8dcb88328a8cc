// The per-block loop of TsdfIntegrator::integrateDepth (tsdf_integrator.h):
// every voxel of one 8^3 block is projected into a prepared depth image
// (DepthIndex) and updated when it lies in front of the measured surface or
// within the truncation band behind it. Two implementations update the same
// voxels to the same bits: a scalar loop, and one over a block row of 8
// voxels at a time with AVX2 (the depths fetched by a gather, the voxels
// loaded and stored as two vectors). The AVX2 code is compiled for that one
// function and chosen at run time when the CPU has AVX2; it uses no fused
// multiply-add, so each lane does the scalar loop's float operations in the
// same order, and a flight does not depend on the CPU it runs on.
#pragma once

#include <cstddef>
#include <cstdint>

#include "surface_nbv/map/tsdf_map.h"

namespace surface_nbv {

// What every block of one frame shares. Positions are in the camera's
// optical frame (z forward), in metres.
struct BlockKernelFrame {
  float ax[3] = {0, 0, 0}, ay[3] = {0, 0, 0}, az[3] = {0, 0, 0};  // one voxel step along the map's x, y, z
  float fx = 0, fy = 0;
  float cx = 0, cy = 0;  // principal point plus half a pixel: floor(u) is the pixel column
  int width = 0, height = 0;
  float far = 0;          // max range plus truncation: voxels beyond are not looked at
  float max_range = 0;    // "free up to max range" (+inf) pixels carve up to here
  float truncation = 0;
  float frame_weight = 1;  // times 1 / z^2
  float max_weight = 0;    // <= 0: no cap
  bool dropoff = false;    // TsdfConfig::weight_dropoff
  float dropoff_start = 0, dropoff_scale = 0;
  const float* usable = nullptr;       // DepthIndex::usableData()
  const uint8_t* silhouette = nullptr;  // DepthIndex::silhouetteData()
};

enum class KernelIsa { kScalar, kAvx2 };

// AVX2 when this CPU has it, else scalar.
KernelIsa bestKernelIsa();

// Updates the block's voxels; p0 is the centre of its voxel (0, 0, 0) in the
// camera frame. Returns the voxels updated. kAvx2 on a CPU without AVX2 runs
// the scalar loop.
size_t integrateBlock(const BlockKernelFrame& frame, const float p0[3], TsdfBlock* block, KernelIsa isa);

}  // namespace surface_nbv
