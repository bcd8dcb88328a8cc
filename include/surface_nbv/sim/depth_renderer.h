// Renders depth images of a RaycastScene with Embree ray packets of 16
// (4 x 4 pixel tiles), 8 (4 x 2) or 4 (2 x 2) rays, bands of rows shared
// among `threads` worker threads (the calling thread is one of them). The
// width defaults to the widest Embree traces natively on the CPU: a packet
// wider than that is traced as narrower ones and costs more (scripts/bench
// sim compares them). Every width gives the same image. Output is z in the
// optical frame in metres; REP 117: +Inf for no return within max range,
// -Inf for a surface closer than min range.
// Noise (if the camera's noise_k > 0) and the rest of the sensor model
// (CameraConfig::sensor, sensor_model.h) are pure functions of (seed, frame
// index, pixel), so an image repeats exactly whatever the thread count: the
// renderer traces the true depth, then measures it (applySensorModel).
// Thread safety: render() is const; one renderer may serve many threads.
#pragma once

#include <cstdint>
#include <vector>

#include "surface_nbv/common.h"
#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sensor/depth_image.h"
#include "surface_nbv/sim/raycast_scene.h"

namespace surface_nbv {

class DepthRenderer {
 public:
  // `scene` must outlive the renderer. threads < 1 is treated as 1.
  // packet_width: 4, 8 or 16 rays; anything else takes the scene's
  // nativePacketWidth().
  DepthRenderer(const RaycastScene& scene, const DepthCamera& camera, int threads = 1, int packet_width = 0);

  // T_W_C: pose of the optical frame in the scene frame.
  void render(const Transform& T_W_C, DepthImage* image, uint64_t frame_index = 0) const;

  const DepthCamera& camera() const { return camera_; }
  int threads() const { return threads_; }
  int packetWidth() const { return packet_width_; }

 private:
  // One frame's rays, R (x_col, y_row, 1) in the world, from products formed
  // once per frame: a column's R(:,0) x_col and a row's R(:,1) y_row, summed
  // as Eigen sums R * Vector3d(x, y, 1) (depth_renderer.cpp).
  struct FrameRays {
    Eigen::Vector3f origin;
    double r02 = 0.0, r12 = 0.0;
    std::vector<double> col_x, col_y, col_z;  // padded to whole tiles
    std::vector<double> row_x, row_y, row_z;  // row_z includes R(2,2)
  };
  // Where traced tiles go: REP 117 depths, or (raw) the true hit depth and
  // +Inf for no hit, with each hit's |cos| of incidence when asked for.
  struct TileOutput {
    DepthImage* image;
    float* cos_incidence;
    bool raw;
  };
  void frameRays(const Transform& T_W_C, FrameRays* rays) const;
  void traceRows(const Transform& T_W_C, DepthImage* image, std::vector<float>* cos_incidence, bool raw) const;
  void renderRows(const FrameRays& rays, int row_begin, int row_end, const TileOutput& out) const;
  template <typename Packet, int TileW, int TileH>
  void renderTiles(const FrameRays& rays, int row_begin, int row_end, const TileOutput& out) const;

  const RaycastScene& scene_;
  DepthCamera camera_;
  int threads_;
  int packet_width_;
  // The camera's pixel rays (x / z per column, y / z per row), as pixelRay()
  // computes them, so a frame does no divisions.
  std::vector<double> ray_x_, ray_y_;
};

// Stereo-like Gaussian depth noise, sigma = k z^2, drawn from a counter-based
// generator keyed by (seed, frame, pixel).
float noisyDepth(float z, double k, uint64_t seed, uint64_t frame, uint64_t pixel);

}  // namespace surface_nbv
