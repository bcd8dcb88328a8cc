// Renders depth images of a RaycastScene with Embree 16-wide ray packets
// (4 x 4 pixel tiles), bands of rows shared among `threads` worker threads
// (the calling thread is one of them). Output is z in the optical
// frame in metres; REP 117: +Inf for no return within max range, -Inf for a
// surface closer than min range.
// Noise (if the camera's noise_k > 0) is a pure function of (seed, frame
// index, pixel), so an image repeats exactly whatever the thread count.
// Thread safety: render() is const; one renderer may serve many threads.
#pragma once

#include <cstdint>
#include <vector>

#include "surface_nbv/common.h"
#include "surface_nbv/sim/depth_camera.h"
#include "surface_nbv/sim/depth_image.h"
#include "surface_nbv/sim/raycast_scene.h"

namespace surface_nbv {

class DepthRenderer {
 public:
  // `scene` must outlive the renderer. threads < 1 is treated as 1.
  DepthRenderer(const RaycastScene& scene, const DepthCamera& camera, int threads = 1);

  // T_W_C: pose of the optical frame in the scene frame.
  void render(const Transform& T_W_C, DepthImage* image, uint64_t frame_index = 0) const;

  const DepthCamera& camera() const { return camera_; }
  int threads() const { return threads_; }

 private:
  void renderRows(const Transform& T_W_C, int row_begin, int row_end, uint64_t frame_index, DepthImage* image) const;

  const RaycastScene& scene_;
  DepthCamera camera_;
  int threads_;
  // The camera's pixel rays (x / z per column, y / z per row), as pixelRay()
  // computes them, so a frame does no divisions.
  std::vector<double> ray_x_, ray_y_;
};

// Stereo-like Gaussian depth noise, sigma = k z^2, drawn from a counter-based
// generator keyed by (seed, frame, pixel).
float noisyDepth(float z, double k, uint64_t seed, uint64_t frame, uint64_t pixel);

}  // namespace surface_nbv
