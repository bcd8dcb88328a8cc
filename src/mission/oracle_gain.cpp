#include "surface_nbv/mission/oracle_gain.h"

#include <cmath>

#include "surface_nbv/sensor/camera_mount.h"

namespace surface_nbv {

bool surfaceObserved(const TsdfMap& map, const Eigen::Vector3d& p) {
  Eigen::Vector3i v;
  if (!map.voxelIndex(p, &v)) return false;
  const float band = static_cast<float>(map.voxelSize());
  const float w_th = map.config().w_th;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const TsdfVoxel* voxel = map.voxel(v + Eigen::Vector3i(dx, dy, dz));
        if (voxel != nullptr && voxel->w >= w_th && std::abs(voxel->phi) <= band) return true;
      }
  return false;
}

OracleGain::OracleGain(const RaycastScene& scene, const CameraConfig& camera, std::vector<Eigen::Vector3d> points)
    : scene_(scene),
      camera_(camera),
      unobserved_(std::move(points)) {}

void OracleGain::update(const TsdfMap& map) {
  std::vector<Eigen::Vector3d> left;
  left.reserve(unobserved_.size());
  for (const Eigen::Vector3d& p : unobserved_)
    if (!surfaceObserved(map, p)) left.push_back(p);
  unobserved_ = std::move(left);
}

double OracleGain::operator()(const Eigen::Vector4d& q) const {
  const Transform T_W_C = levelBodyPose(q.head<3>(), q.w()) * opticalInBody(camera_.config());
  const Transform T_C_W = T_W_C.inverse();
  const Eigen::Vector3d origin = T_W_C.translation();
  // The true surface stops a ray this far before the point: the point's own face.
  constexpr double kOwnFace = 0.05;
  size_t seen = 0;
  for (const Eigen::Vector3d& p : unobserved_) {
    if (!camera_.sees(T_C_W * p)) continue;
    const Eigen::Vector3d ray = p - origin;
    const double dist = ray.norm();
    double t_hit = 0.0;
    if (scene_.intersect(origin, ray / dist, 0.0, dist - kOwnFace, &t_hit)) continue;
    ++seen;
  }
  return static_cast<double>(seen);
}

}  // namespace surface_nbv
