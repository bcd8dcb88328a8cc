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

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "surface_nbv/map/tsdf_config.h"
#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/sensor/depth_camera.h"

namespace surface_nbv {

// The truncation band `trunc` and the share of an update's weight kept with
// TsdfConfig::weight_dropoff: 1 down to sdf = -start (one voxel), then
// falling linearly to 0 at -trunc. With a noisy sensor (setNoise: the
// camera's sensor model, sensor_model.h) the full weight reaches down to the
// larger of one voxel and 2 sigma(z) at the voxel's depth z: measurements
// that noise put behind the surface are not down-weighted against those it
// put in front, which would pull the surface into the object (issue #40).
struct WeightDropoff {
  bool on = false;
  float start = 0.0f, trunc = 0.0f, scale = 0.0f;
  bool noisy = false;
  float noise0 = 0.0f, noise1 = 0.0f, noise2 = 0.0f;  // 2 sigma(z) = noise0 + (noise1 + noise2 z) z

  WeightDropoff() = default;
  explicit WeightDropoff(const TsdfConfig& c);
  // Takes the camera's axial noise model; a perfect camera changes nothing.
  void setNoise(const CameraConfig& camera);
  float share(float sdf, float z) const {
    if (!on) return 1.0f;
    if (!noisy) return sdf < -start ? (trunc + sdf) * scale : 1.0f;
    const float s = std::max(start, noise0 + (noise1 + noise2 * z) * z);
    return sdf < -s ? (trunc + sdf) / (trunc - s) : 1.0f;  // sdf >= -trunc, so s < trunc there
  }
};

// A voxel's update by one measurement: phi the weighted running average, w
// the sum of the weights, capped at max_weight when that is > 0.
inline void updateVoxel(TsdfVoxel* v, float sdf, float weight, float max_weight) {
  const float w = v->w + weight;
  v->phi = (v->phi * v->w + sdf * weight) / w;
  v->w = max_weight > 0.0f ? std::min(w, max_weight) : w;
}

// What every block of one frame shares. Positions are in the camera's
// optical frame (z forward), in metres.
struct BlockKernelFrame {
  float ax[3] = {0, 0, 0}, ay[3] = {0, 0, 0}, az[3] = {0, 0, 0};  // one voxel step along the map's x, y, z
  float fx = 0, fy = 0;
  float cx = 0, cy = 0;  // principal point plus half a pixel: floor(u) is the pixel column
  int width = 0, height = 0;
  float far = 0;          // max range plus truncation: voxels beyond are not looked at
  float max_range = 0;    // "free up to max range" (+inf) pixels carve up to here
  float frame_weight = 1;  // times 1 / z^2
  float max_weight = 0;    // <= 0: no cap
  WeightDropoff dropoff;   // the truncation band and, when on, the drop-off
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
