// A gain that knows the ground truth, for diagnostics: how many points of the
// true surface not yet observed in the map a configuration would see (inside
// the camera's frustum and depth range, not hidden by the true mesh).
// `nbv_mission --oracle-gain N` ranks the tour's first N configurations by it
// (Explorer::setHeadGain), which bounds what a better model of the unseen
// surface could win with eq. 2's viewpoints and the same flight.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/sensor/depth_camera.h"
#include "surface_nbv/sim/raycast_scene.h"

namespace surface_nbv {

// A known surface voxel (w >= W_th, |phi| within one voxel) lies within one
// voxel of p: the map has observed the surface at p.
bool surfaceObserved(const TsdfMap& map, const Eigen::Vector3d& p);

class OracleGain {
 public:
  // `scene` (not owned) is the true mesh; `points` sample its surface.
  OracleGain(const RaycastScene& scene, const CameraConfig& camera, std::vector<Eigen::Vector3d> points);

  // Keeps the points the map has not observed yet.
  void update(const TsdfMap& map);
  // The unobserved points a level camera at q = [x, y, z, yaw] would see.
  double operator()(const Eigen::Vector4d& q) const;
  size_t unobserved() const { return unobserved_.size(); }

 private:
  const RaycastScene& scene_;
  DepthCamera camera_;
  std::vector<Eigen::Vector3d> unobserved_;
};

}  // namespace surface_nbv
