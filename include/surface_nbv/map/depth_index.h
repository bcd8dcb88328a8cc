// A depth image prepared for projective integration: per pixel the usable
// depth (a measurement, +inf for "free up to max range", NaN for nothing),
// a silhouette flag (next to a depth jump larger than the truncation or to a
// pixel without usable depth), and a max-depth pyramid over 8 x 8 tiles that
// bounds the farthest usable depth in any pixel rectangle with four look-ups,
// so whole blocks hidden behind surfaces are skipped, and a min-depth pyramid
// of the measured depths, so blocks far in front of every surface can be. Buffers are kept
// between frames. Not thread safe; build() itself uses `threads`.
#pragma once

#include <cstdint>
#include <vector>

#include "surface_nbv/map/tsdf_config.h"
#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sensor/depth_image.h"

namespace surface_nbv {

class DepthIndex {
 public:
  // Returns the number of invalid pixels (NaN, +-Inf, zero, outside the
  // range); `policy` says which of them clear free space up to max range.
  // The min-depth pyramid is built only with `nearest` (band allocation).
  size_t build(const DepthCamera& camera, const DepthImage& depth, float truncation, InvalidPixelPolicy policy,
               int threads, bool nearest = false);

  float usable(size_t pixel) const { return usable_[pixel]; }
  bool silhouette(size_t pixel) const { return silhouette_[pixel] != 0; }
  const float* usableData() const { return usable_.data(); }
  const uint8_t* silhouetteData() const { return silhouette_.data(); }
  // Farthest depth any pixel in [u0, u1] x [v0, v1] can reach (max range for
  // cleared pixels), or -inf when none can; an upper bound, never less.
  float maxDepthOver(int u0, int v0, int u1, int v1) const;
  // Nearest measured depth in the rectangle (cleared pixels do not count),
  // or +inf when it holds none; a lower bound, never more. -inf when the
  // last build() skipped the pyramid.
  float minDepthOver(int u0, int v0, int u1, int v1) const;

 private:
  struct Level {
    int width = 0, height = 0;
    std::vector<float> max_depth;
    std::vector<float> min_depth;  // measured depths only
  };
  std::vector<float> usable_;
  std::vector<float> key_;  // usable depth, or kFar where there is none (silhouette test)
  std::vector<uint8_t> silhouette_;
  std::vector<Level> levels_;  // levels_[k]: cells of 8 * 2^k pixels
};

}  // namespace surface_nbv
