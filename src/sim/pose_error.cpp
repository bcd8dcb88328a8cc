#include "surface_nbv/sim/pose_error.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "surface_nbv/sensor/sensor_model.h"

namespace surface_nbv {
namespace {

// The pose error's draws use the sensor model's generator with "pixels"
// beyond any image (2^40 + component), so they never repeat a depth draw.
constexpr uint64_t kPoseKey = 1ull << 40;
enum : uint64_t { kDriftX = 0, kDriftY, kDriftZ, kDriftYaw, kJitterX, kJitterY, kJitterZ, kJitterRoll, kJitterPitch,
                  kJitterYaw };

double draw(uint64_t seed, uint64_t frame, uint64_t component) {
  return sensorGaussian(seed, frame, kPoseKey + component, 0);
}

}  // namespace

Status PoseErrorConfig::validate() const {
  auto check = [](double v, double max, const char* key) {
    if (std::isfinite(v) && v >= 0.0 && v <= max) return Status::Ok();
    return Status::Error(std::string(key) + " expected in [0, " + std::to_string(max) + "], got " + std::to_string(v));
  };
  const Status checks[] = {check(drift_rate, 1.0, "pose_drift_rate"), check(yaw_drift_deg, 10.0, "pose_yaw_drift_deg"),
                           check(jitter_position, 1.0, "pose_jitter"), check(jitter_angle_deg, 10.0, "pose_jitter_deg")};
  for (const Status& s : checks) {
    if (!s) return s;
  }
  return Status::Ok();
}

PoseErrorModel::PoseErrorModel(const PoseErrorConfig& config) : config_(config) {}

void PoseErrorModel::advance(const Eigen::Vector3d& p_W, uint64_t frame) {
  if (!enabled()) return;
  if (!started_) {
    started_ = true;
    last_p_ = p_W;
  }
  const double ds = (p_W - last_p_).norm();
  last_p_ = p_W;
  distance_ += ds;
  if (ds > 0.0 && (config_.drift_rate > 0.0 || config_.yaw_drift_deg > 0.0)) {
    const uint64_t seed = config_.seed;
    const double root = std::sqrt(ds);
    const Eigen::Vector3d dt = config_.drift_rate * root *
                               Eigen::Vector3d(draw(seed, frame, kDriftX), draw(seed, frame, kDriftY),
                                               draw(seed, frame, kDriftZ));
    const double dyaw = config_.yaw_drift_deg * M_PI / 180.0 * root * draw(seed, frame, kDriftYaw);
    // D <- Trans(dt) * D * (yaw dyaw about p_W): the true position moves by
    // dt alone, later motion turns with the yaw.
    Transform about = Transform::Identity();
    about.linear() = Eigen::AngleAxisd(dyaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    about.translation() = p_W - about.linear() * p_W;
    D_ = D_ * about;
    D_.pretranslate(dt);
    yaw_ += dyaw;
  }
  stats_.add((D_ * p_W - p_W).norm(), yaw_);
}

void PoseErrorStats::add(double position, double yaw) {
  ++frames;
  sum_sq_position_ += position * position;
  sum_sq_yaw_ += yaw * yaw;
  final_position = position;
  max_position = std::max(max_position, position);
  rms_position = std::sqrt(sum_sq_position_ / frames);
  final_yaw_deg = std::abs(yaw) * 180.0 / M_PI;
  rms_yaw_deg = std::sqrt(sum_sq_yaw_ / frames) * 180.0 / M_PI;
}

void PoseErrorStats::addPose(const Transform& T, const Transform& T_true) {
  // The yaw between the optical axes about the world's z.
  const Eigen::Vector3d a = T.linear().col(2), b = T_true.linear().col(2);
  add((T.translation() - T_true.translation()).norm(),
      std::atan2(b.x() * a.y() - b.y() * a.x(), b.x() * a.x() + b.y() * a.y()));
}

Transform PoseErrorModel::truePose(const Transform& T_estimate) const {
  if (!enabled()) return T_estimate;
  return D_ * T_estimate;
}

Transform PoseErrorModel::reportedPose(const Transform& T_estimate, uint64_t frame) const {
  if (!(config_.jitter_position > 0.0 || config_.jitter_angle_deg > 0.0)) return T_estimate;
  const uint64_t seed = config_.seed;
  const double a = config_.jitter_angle_deg * M_PI / 180.0;
  Transform J = Transform::Identity();
  J.linear() = (Eigen::AngleAxisd(a * draw(seed, frame, kJitterYaw), Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(a * draw(seed, frame, kJitterPitch), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(a * draw(seed, frame, kJitterRoll), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  J.translation() = config_.jitter_position * Eigen::Vector3d(draw(seed, frame, kJitterX), draw(seed, frame, kJitterY),
                                                              draw(seed, frame, kJitterZ));
  return T_estimate * J;
}

}  // namespace surface_nbv
