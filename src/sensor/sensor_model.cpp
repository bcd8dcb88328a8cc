#include "surface_nbv/sensor/sensor_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sensor/depth_image.h"
#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {
namespace {

uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

double toUnit(uint64_t x) { return (static_cast<double>(x >> 11) + 0.5) * (1.0 / 9007199254740992.0); }

// noisyDepth()'s key of (seed, frame, pixel); other streams hash it again.
uint64_t frameKey(uint64_t seed, uint64_t frame) { return splitmix64(seed) ^ splitmix64(frame + 0x632BE59BD9B4E019ull); }
uint64_t streamKey(uint64_t pixel_key, uint64_t stream) {
  return stream == 0 ? pixel_key : splitmix64(pixel_key ^ (stream * 0xA0761D6478BD642Full));
}
uint64_t pixelKey(uint64_t seed, uint64_t frame, uint64_t pixel, uint64_t stream) {
  return streamKey(splitmix64(frameKey(seed, frame) ^ pixel), stream);
}
double uniformOfKey(uint64_t key) { return toUnit(splitmix64(key ^ 0x8BB84B93962EACC9ull)); }

// Streams of the per-pixel draws.
enum : uint64_t { kAxial = 0, kLateralU = 1, kLateralV = 2, kGrazing = 3, kRandom = 4, kPatch = 5 };

Status expectUnit(double v, const char* key) {
  if (std::isfinite(v) && v >= 0.0 && v <= 1.0) return Status::Ok();
  return Status::Error(std::string("camera/") + key + " expected in [0, 1], got " + std::to_string(v));
}

}  // namespace

bool SensorModelConfig::enabled() const {
  return noise_sigma0 > 0.0 || noise_sigma1 > 0.0 || lateral_noise_px > 0.0 || grazing_dropout_deg > 0.0 ||
         dropout_rate > 0.0 || dropout_patch_fraction > 0.0 || quantization > 0.0;
}

Status SensorModelConfig::validate() const {
  auto nonNegative = [](double v, const char* key, double max) {
    if (std::isfinite(v) && v >= 0.0 && v <= max) return Status::Ok();
    return Status::Error(std::string("camera/") + key + " expected in [0, " + std::to_string(max) + "], got " +
                         std::to_string(v));
  };
  const Status checks[] = {
      nonNegative(noise_sigma0, "noise_sigma0", 1.0),
      nonNegative(noise_sigma1, "noise_sigma1", 1.0),
      nonNegative(lateral_noise_px, "lateral_noise_px", 10.0),
      std::isfinite(grazing_dropout_deg) && grazing_dropout_deg >= 0.0 && grazing_dropout_deg < 90.0
          ? Status::Ok()
          : Status::Error("camera/grazing_dropout_deg expected in [0, 90) (0: off), got " +
                          std::to_string(grazing_dropout_deg)),
      expectUnit(dropout_rate, "dropout_rate"),
      expectUnit(dropout_patch_fraction, "dropout_patch_fraction"),
      std::isfinite(dropout_patch_size) && dropout_patch_size > 0.0
          ? Status::Ok()
          : Status::Error("camera/dropout_patch_size expected > 0 m, got " + std::to_string(dropout_patch_size)),
      expectUnit(dropout_patch_rate, "dropout_patch_rate"),
      nonNegative(quantization, "quantization", 1.0),
  };
  for (const Status& s : checks) {
    if (!s) return s;
  }
  return Status::Ok();
}

double axialSigma(const SensorModelConfig& sensor, double noise_k, double z) {
  return sensor.noise_sigma0 + sensor.noise_sigma1 * z + noise_k * z * z;
}

double normalQuantile(double p) {
  // Acklam's rational approximation (relative error below 1.2e-9), one log
  // in the tails only: a third of Box-Muller's cost per draw.
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01,  -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  constexpr double kLow = 0.02425;
  if (p < kLow) {
    const double q = std::sqrt(-2.0 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  if (p > 1.0 - kLow) return -normalQuantile(1.0 - p);
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
}

namespace {
double gaussianOfKey(uint64_t key) { return normalQuantile(toUnit(splitmix64(key))); }
}  // namespace

double sensorGaussian(uint64_t seed, uint64_t frame, uint64_t pixel, uint64_t stream) {
  return gaussianOfKey(pixelKey(seed, frame, pixel, stream));
}

double sensorUniform(uint64_t seed, uint64_t frame, uint64_t pixel, uint64_t stream) {
  return uniformOfKey(pixelKey(seed, frame, pixel, stream));
}

bool inDropoutPatch(const SensorModelConfig& sensor, uint64_t seed, const Eigen::Vector3d& p_W) {
  if (!(sensor.dropout_patch_fraction > 0.0)) return false;
  const Eigen::Vector3d c = (p_W / sensor.dropout_patch_size).array().floor();
  uint64_t h = splitmix64(seed ^ 0x5DEECE66DA3B1F27ull);
  for (int i = 0; i < 3; ++i) h = splitmix64(h ^ static_cast<uint64_t>(static_cast<int64_t>(c[i])));
  return toUnit(h) < sensor.dropout_patch_fraction;
}

void applySensorModel(const DepthCamera& camera, const Transform& T_W_C, uint64_t frame, const DepthImage& raw,
                      const std::vector<float>& cos_incidence, DepthImage* out, int threads) {
  const CameraConfig& cfg = camera.config();
  const SensorModelConfig& s = cfg.sensor;
  const int width = raw.width, height = raw.height;
  out->resize(width, height);
  constexpr float kInf = std::numeric_limits<float>::infinity();
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  const uint64_t seed = cfg.noise_seed;
  const bool lateral = s.lateral_noise_px > 0.0;
  const bool grazing = s.grazing_dropout_deg > 0.0 && cos_incidence.size() == raw.data.size();
  const double cos_start = std::cos(s.grazing_dropout_deg * M_PI / 180.0);
  const double grazing_span = 0.5 * M_PI - s.grazing_dropout_deg * M_PI / 180.0;
  const bool patches = s.dropout_patch_fraction > 0.0;
  const bool noisy = axialSigma(s, cfg.noise_k, 1.0) > 0.0;
  const double min_z = cfg.min_range, max_z = cfg.max_range;

  // A lateral offset is round(lateral_noise_px g), g standard normal: drawn
  // from its distribution over whole pixels, P(offset <= k) = Phi((k + 0.5) / sigma).
  std::vector<double> offset_cdf;
  int max_offset = 0;
  if (lateral) {
    max_offset = static_cast<int>(std::ceil(6.0 * s.lateral_noise_px));
    for (int k = -max_offset; k < max_offset; ++k) {
      offset_cdf.push_back(0.5 * std::erfc(-(k + 0.5) / (s.lateral_noise_px * std::sqrt(2.0))));
    }
  }
  auto lateralOffset = [&](double u) {
    int k = 0;
    while (k < static_cast<int>(offset_cdf.size()) && u >= offset_cdf[k]) ++k;
    return k - max_offset;
  };

  // The draws of sensorGaussian() / sensorUniform(), their common part once a frame and once a pixel.
  const uint64_t frame_key = frameKey(seed, frame);
  auto pixelValue = [&](int row, int col) -> float {
    const uint64_t pixel_key = splitmix64(frame_key ^ (static_cast<uint64_t>(row) * width + col));
    auto uniform = [pixel_key](uint64_t stream) { return uniformOfKey(streamKey(pixel_key, stream)); };
    int src_row = row, src_col = col;
    if (lateral) {
      src_col = std::clamp(col + lateralOffset(uniform(kLateralU)), 0, width - 1);
      src_row = std::clamp(row + lateralOffset(uniform(kLateralV)), 0, height - 1);
    }
    const size_t src = static_cast<size_t>(src_row) * width + src_col;
    const double z0 = raw.data[src];
    if (!std::isfinite(z0)) return kInf;  // no return within range
    if (grazing) {
      const double c = cos_incidence[src];
      if (c < cos_start) {
        const double p = (std::acos(std::clamp(c, 0.0, 1.0)) - (0.5 * M_PI - grazing_span)) / grazing_span;
        if (uniform(kGrazing) < p) return kNaN;
      }
    }
    if (s.dropout_rate > 0.0 && uniform(kRandom) < s.dropout_rate) return kNaN;
    if (patches) {
      const Eigen::Vector3d p_W = T_W_C * (camera.pixelRay(src_col, src_row) * z0);
      if (inDropoutPatch(s, seed, p_W) && uniform(kPatch) < s.dropout_patch_rate) {
        return kNaN;
      }
    }
    double z = z0;
    if (noisy) z = z0 + axialSigma(s, cfg.noise_k, z0) * gaussianOfKey(streamKey(pixel_key, kAxial));
    if (z < min_z) return -kInf;
    // A surface the noise pushed past max range was measured, not missed:
    // invalid, so that it never clears the space in front of it as +Inf does.
    if (!(z <= max_z)) return kNaN;
    if (s.quantization > 0.0) z = std::round(z / s.quantization) * s.quantization;
    return static_cast<float>(z);
  };

  constexpr int kRowsPerTask = 8;
  const size_t bands = static_cast<size_t>((height + kRowsPerTask - 1) / kRowsPerTask);
  parallelFor(bands, threads, [&](size_t band) {
    const int row_end = std::min(height, static_cast<int>(band + 1) * kRowsPerTask);
    for (int row = static_cast<int>(band) * kRowsPerTask; row < row_end; ++row) {
      for (int col = 0; col < width; ++col) out->at(row, col) = pixelValue(row, col);
    }
  });
}

}  // namespace surface_nbv
