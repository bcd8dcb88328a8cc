// Fuses depth into a TsdfMap (docs/method.md, "TSDF map"). Depth images are
// integrated projectively: every voxel of every block that can be in the
// camera frustum (up to max range plus truncation, and not entirely behind
// the measured surfaces) is projected into the image; with the measured depth
// d at that pixel and the voxel's depth z, sdf = d - z, clamped to the
// truncation distance t, and the voxel is updated when sdf >= -t:
//   phi <- (w phi + w_new sdf) / (w + w_new),  w <- w + w_new,  w_new = 1 / z^2
// (weights optionally capped; with TsdfConfig::weight_dropoff, w_new falls
// linearly from sdf = -voxel_size to nothing at -t). Free space in front of
// surfaces is carved this way. Pixels on a silhouette (next to a depth jump
// larger than t or to a pixel without depth) only carve: behind them a voxel
// just past an edge cannot be told from one inside the object, and updating
// it would thicken convex edges by up to t. Point clouds are integrated by
// casting each ray through the voxels with the same update, distances
// measured along the ray.
// Thread safety: one integration at a time per map; it uses config.threads
// (or setThreads()).
#pragma once

#include <cmath>

#include <cstdint>
#include <vector>

#include "surface_nbv/common.h"
#include "surface_nbv/map/depth_index.h"
#include "surface_nbv/map/integrate_kernel.h"
#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sensor/depth_image.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct IntegrationStats {
  size_t blocks_considered = 0;  // in the frustum's bounding box
  size_t blocks_updated = 0;
  size_t voxels_updated = 0;
  size_t blocks_refused = 0;     // allocation refused (cap or bounds)
  size_t invalid_pixels = 0;
};

class TsdfIntegrator {
 public:
  explicit TsdfIntegrator(TsdfMap* map);

  // T_W_C: optical frame in the world. The image must match the camera size.
  Status integrateDepth(const DepthCamera& camera, const DepthImage& depth, const Transform& T_W_C,
                        IntegrationStats* stats = nullptr);

  // points_S in the sensor frame (origin = sensor), sensor pose T_W_S.
  // Points farther than max_range are treated as invalid pixels are.
  Status integratePoints(const std::vector<Eigen::Vector3f>& points_S, const Transform& T_W_S, double max_range,
                         IntegrationStats* stats = nullptr);

  // Declares the ball (centre, radius) free where the map does not know it
  // yet: every voxel whose centre lies inside and whose weight is below W_th
  // gets phi = truncation and w = W_th. Observed voxels are left as they are.
  // The space a UAV occupies at take-off is free, but a depth camera cannot
  // see it (min range). Returns the voxels changed; error for a bad ball.
  Status markFree(const Eigen::Vector3d& center, double radius, size_t* changed = nullptr);

  // Each integrated frame counts as `scale` frames (weight scale * 1 / z^2):
  // a stream decimated from a camera rate to a lower integration rate keeps
  // the weight per second of the full stream (1 = every frame integrated).
  // Consecutive frames of a camera at 30 Hz moving at 0.5 m/s are 1.7 cm
  // apart, so one frame of weight k stands for k of them. Values <= 0 or
  // non-finite are ignored.
  void setWeightScale(double scale) {
    if (std::isfinite(scale) && scale > 0.0) weight_scale_ = static_cast<float>(scale);
  }
  float weightScale() const { return weight_scale_; }
  // Threads of the next integrations; 0 (the default) = the map's config.threads.
  void setThreads(int threads) { threads_ = threads > 0 ? threads : 0; }
  int threads() const { return threads_ > 0 ? threads_ : map_->config().threads; }
  // The per-block loop of depth images (integrate_kernel.h): the best this CPU
  // has by default; kScalar for comparisons. Both give the same voxels.
  void setKernelIsa(KernelIsa isa) { kernel_isa_ = isa; }
  KernelIsa kernelIsa() const { return kernel_isa_; }

 private:
  // Blocks that can be in view and not hidden behind surfaces, allocated.
  std::vector<TsdfBlock*> candidateBlocks(const DepthCamera& camera, const Transform& T_W_C, IntegrationStats* stats);

  TsdfMap* map_;
  DepthIndex index_;
  float weight_scale_ = 1.0f;
  int threads_ = 0;
  KernelIsa kernel_isa_ = bestKernelIsa();
};

}  // namespace surface_nbv
