// Pinhole depth camera in the optical frame (z forward, x right, y down).
// Pixel (col, row) has its centre at integer coordinates, as in ROS
// CameraInfo: the image spans [-0.5, width - 0.5] and the principal point is
// the image centre, so the outer pixel edges lie exactly on the FOV.
// Depth is z in metres; anything outside [min_range, max_range] is no return.
#pragma once

#include <cstdint>

#include <Eigen/Core>

#include "surface_nbv/sensor/sensor_model.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct CameraConfig {
  int width = 640;
  int height = 480;
  double hfov_deg = 90.0;
  double vfov_deg = 60.0;
  double min_range = 1.6;   // m, on z
  double max_range = 8.0;   // m, on z
  double rate_hz = 30.0;
  // Stereo-like noise: sigma = noise_k * z^2 [1/m]; 0 disables it.
  double noise_k = 0.0;
  uint64_t noise_seed = 1;  // every draw of the sensor model too
  // The rest of a real sensor (sensor_model.h): ToF-like noise, lateral edge
  // noise, dropouts, quantisation. All off by default.
  SensorModelConfig sensor;
  // Mount pitch [deg] about the body's y axis, positive down: the UAV flies
  // level, so the optical axis stays this far below the horizon (RotorS
  // mounts its VI-sensor 0.1 rad = 5.73 deg down). |pitch| < 90 - vfov / 2.
  double pitch_deg = 0.0;

  // Elevations [deg] of a pose above a point that keep the point inside the
  // vertical FOV, `margin_deg` within its edges: the level UAV's camera looks
  // up to vfov / 2 - pitch and down to vfov / 2 + pitch.
  double minPoseElevationDeg(double margin_deg = 0.0) const { return -(0.5 * vfov_deg - pitch_deg - margin_deg); }
  double maxPoseElevationDeg(double margin_deg = 0.0) const { return 0.5 * vfov_deg + pitch_deg - margin_deg; }

  // Names the first bad key, e.g. "camera/hfov_deg expected in (0, 180)".
  Status validate() const;
};

class DepthCamera {
 public:
  explicit DepthCamera(const CameraConfig& config);
  // Explicit intrinsics (e.g. from a CameraInfo): the size and depth range
  // come from `config`, its FOV fields are recomputed from fx and fy.
  DepthCamera(const CameraConfig& config, double fx, double fy, double cx, double cy);

  const CameraConfig& config() const { return config_; }
  int width() const { return config_.width; }
  int height() const { return config_.height; }
  double fx() const { return fx_; }
  double fy() const { return fy_; }
  double cx() const { return cx_; }
  double cy() const { return cy_; }

  // Ray through pixel (col, row) in the optical frame, scaled so that z = 1:
  // a hit at parameter t along it is at depth z = t.
  Eigen::Vector3d pixelRay(double col, double row) const {
    return Eigen::Vector3d((col - cx_) / fx_, (row - cy_) / fy_, 1.0);
  }
  // Projects p_C; false behind the camera or outside the image.
  bool project(const Eigen::Vector3d& p_C, double* col, double* row) const;
  // True if p_C projects inside the image and lies within the depth range.
  bool sees(const Eigen::Vector3d& p_C) const;
  bool depthInRange(double z) const { return z >= config_.min_range && z <= config_.max_range; }

 private:
  CameraConfig config_;
  double fx_, fy_, cx_, cy_;
};

}  // namespace surface_nbv
