// What a real depth camera does to the true depth (issue #40), applied by
// DepthRenderer after it traced the scene, so depth_sim and nbv_mission
// measure the same way:
//   - axial noise, Gaussian with sigma(z) = noise_sigma0 + noise_sigma1 z
//     + CameraConfig::noise_k z^2: stereo-like (k z^2, the disparity error
//     of a fixed baseline) and ToF-like (constant + linear) in one model.
//   - lateral edge noise: each pixel measures the depth of a pixel shifted
//     by a Gaussian offset of lateral_noise_px (rounded to whole pixels), so
//     flat surfaces barely move and depth edges fray (flying pixels).
//   - invalid pixels (NaN: no measurement, never carves free space):
//     grazing angles (past grazing_dropout_deg of incidence the dropout
//     probability grows linearly to 1 at 90 deg), random dropouts
//     (dropout_rate per pixel and frame) and dark / specular-like patches:
//     a seeded share dropout_patch_fraction of the world's
//     dropout_patch_size cubes, fixed on the surface whatever the view,
//     whose pixels drop with probability dropout_patch_rate in every frame.
//   - quantisation: depths rounded to `quantization` metres (0.001 is what
//     16UC1 millimetres carry).
// Every draw is a pure function of (CameraConfig::noise_seed, frame index,
// pixel) (the patches: of the seed and the cube), so an image repeats
// exactly whatever the thread count. The axial draw is noisyDepth()'s. A
// surface the noise pushes past max range is invalid (NaN), not +Inf: it was
// measured, so it must not clear the space in front of it.
// Every field 0 (the default): the sensor is perfect and nothing runs.
#pragma once

#include <cstdint>
#include <vector>

#include "surface_nbv/common.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

class DepthCamera;
struct DepthImage;

struct SensorModelConfig {
  double noise_sigma0 = 0.0;          // m: constant axial sigma (ToF-like)
  double noise_sigma1 = 0.0;          // sigma per metre of depth (ToF-like linear term)
  double lateral_noise_px = 0.0;      // sigma of the lateral pixel offset [px]
  double grazing_dropout_deg = 0.0;   // incidence angle where dropouts start, in (0, 90); 0: off
  double dropout_rate = 0.0;          // random invalid pixels, per pixel and frame, [0, 1]
  double dropout_patch_fraction = 0.0;  // share of the world's cubes that are dark / specular, [0, 1]
  double dropout_patch_size = 1.0;    // edge of those cubes [m]
  double dropout_patch_rate = 1.0;    // a patch pixel's dropout probability per frame, [0, 1]
  double quantization = 0.0;          // depth step [m]; 0.001 = 16UC1 millimetres; 0: off

  // True when anything beyond the renderer's plain noise_k is modelled.
  bool enabled() const;
  // Names the first bad key, e.g. "camera/dropout_rate expected in [0, 1]".
  Status validate() const;
};

// Axial sigma [m] at depth z of the camera's model (noise_k included).
double axialSigma(const SensorModelConfig& sensor, double noise_k, double z);

// A standard normal draw (the inverse normal CDF of a uniform) and a uniform
// draw in (0, 1), pure functions of (seed, frame, pixel, stream). Stream 0
// of the normal is noisyDepth()'s.
double sensorGaussian(uint64_t seed, uint64_t frame, uint64_t pixel, uint64_t stream);
// The standard normal quantile of p in (0, 1) (relative error < 1.2e-9).
double normalQuantile(double p);
double sensorUniform(uint64_t seed, uint64_t frame, uint64_t pixel, uint64_t stream);

// Whether the world point p_W lies in a dark / specular patch of `seed`.
bool inDropoutPatch(const SensorModelConfig& sensor, uint64_t seed, const Eigen::Vector3d& p_W);

// The measured image from the traced one. `raw`: the hit depth z of every
// pixel (+Inf where the ray hit nothing up to max range), no range limits
// applied; `cos_incidence`: |cos| of each hit's angle of incidence (may be
// empty when grazing dropouts are off). `out` gets REP 117 depths as the
// renderer's (-Inf closer than min range, +Inf beyond max range or no hit)
// and NaN for invalid pixels. Rows are shared among `threads` threads.
void applySensorModel(const DepthCamera& camera, const Transform& T_W_C, uint64_t frame, const DepthImage& raw,
                      const std::vector<float>& cos_incidence, DepthImage* out, int threads = 1);

}  // namespace surface_nbv
