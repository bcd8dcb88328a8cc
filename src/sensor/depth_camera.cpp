#include "surface_nbv/sensor/depth_camera.h"

#include <cmath>
#include <string>

namespace surface_nbv {
namespace {

Status expect(bool ok, const std::string& what) { return ok ? Status::Ok() : Status::Error(what); }

}  // namespace

Status CameraConfig::validate() const {
  const Status checks[] = {
      expect(width > 0 && width <= 16384, "camera/width expected in [1, 16384], got " + std::to_string(width)),
      expect(height > 0 && height <= 16384, "camera/height expected in [1, 16384], got " + std::to_string(height)),
      expect(std::isfinite(hfov_deg) && hfov_deg > 0.0 && hfov_deg < 180.0,
             "camera/hfov_deg expected in (0, 180), got " + std::to_string(hfov_deg)),
      expect(std::isfinite(vfov_deg) && vfov_deg > 0.0 && vfov_deg < 180.0,
             "camera/vfov_deg expected in (0, 180), got " + std::to_string(vfov_deg)),
      expect(std::isfinite(min_range) && min_range >= 0.0,
             "camera/min_range expected >= 0, got " + std::to_string(min_range)),
      expect(std::isfinite(max_range) && max_range > min_range,
             "camera/max_range expected > camera/min_range, got " + std::to_string(max_range)),
      expect(std::isfinite(rate_hz) && rate_hz > 0.0 && rate_hz <= 1000.0,
             "camera/rate_hz expected in (0, 1000], got " + std::to_string(rate_hz)),
      expect(std::isfinite(noise_k) && noise_k >= 0.0, "camera/noise_k expected >= 0, got " + std::to_string(noise_k)),
      expect(std::isfinite(pitch_deg) && std::abs(pitch_deg) < 90.0 - 0.5 * vfov_deg,
             "camera/pitch_deg expected in (-(90 - vfov_deg / 2), 90 - vfov_deg / 2), got " + std::to_string(pitch_deg)),
  };
  for (const Status& s : checks) {
    if (!s) return s;
  }
  return sensor.validate();
}

DepthCamera::DepthCamera(const CameraConfig& config) : config_(config) {
  const double deg = M_PI / 180.0;
  fx_ = 0.5 * config.width / std::tan(0.5 * config.hfov_deg * deg);
  fy_ = 0.5 * config.height / std::tan(0.5 * config.vfov_deg * deg);
  cx_ = 0.5 * (config.width - 1);
  cy_ = 0.5 * (config.height - 1);
}

DepthCamera::DepthCamera(const CameraConfig& config, double fx, double fy, double cx, double cy)
    : config_(config), fx_(fx), fy_(fy), cx_(cx), cy_(cy) {
  config_.hfov_deg = 2.0 * std::atan(0.5 * config.width / fx) * 180.0 / M_PI;
  config_.vfov_deg = 2.0 * std::atan(0.5 * config.height / fy) * 180.0 / M_PI;
}

bool DepthCamera::project(const Eigen::Vector3d& p_C, double* col, double* row) const {
  if (!(p_C.z() > 0.0)) return false;
  const double u = fx_ * p_C.x() / p_C.z() + cx_;
  const double v = fy_ * p_C.y() / p_C.z() + cy_;
  if (!(u >= -0.5 && u <= config_.width - 0.5 && v >= -0.5 && v <= config_.height - 0.5)) return false;
  *col = u;
  *row = v;
  return true;
}

bool DepthCamera::sees(const Eigen::Vector3d& p_C) const {
  double u, v;
  return project(p_C, &u, &v) && depthInRange(p_C.z());
}

}  // namespace surface_nbv
