// A static triangle scene in Embree 3 for ray queries, in the mesh's frame
// (the world frame for scenes). Thread safety: all queries are const and may
// run from many threads at once; construction is not thread safe.
#pragma once

#include <memory>
#include <string>

#include <embree3/rtcore.h>
#include <Eigen/Core>

#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

class RaycastScene {
 public:
  // Builds the BVH. An empty mesh or an Embree failure is an error.
  static Status create(const TriangleMesh& mesh, std::unique_ptr<RaycastScene>* scene);
  ~RaycastScene();
  RaycastScene(const RaycastScene&) = delete;
  RaycastScene& operator=(const RaycastScene&) = delete;

  // Nearest hit along origin + t * direction with t in [t_near, t_far],
  // returns false on a miss. `direction` need not be unit length: t is in its units.
  bool intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_near, double t_far,
                 double* t_hit, int* triangle = nullptr) const;

  RTCScene handle() const { return scene_; }
  size_t numTriangles() const { return num_triangles_; }
  // The widest ray packet Embree traces natively on this CPU: 16 with
  // AVX-512, 8 with AVX2, else 4 (RTC_DEVICE_PROPERTY_NATIVE_RAY*_SUPPORTED).
  int nativePacketWidth() const;

 private:
  RaycastScene() = default;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  size_t num_triangles_ = 0;
};

}  // namespace surface_nbv
