#include "surface_nbv/sim/raycast_scene.h"

#include <cstring>
#include <limits>

namespace surface_nbv {

Status RaycastScene::create(const TriangleMesh& mesh, std::unique_ptr<RaycastScene>* out) {
  if (mesh.empty()) return Status::Error("cannot build a ray casting scene from an empty mesh");
  std::unique_ptr<RaycastScene> rs(new RaycastScene());
  rs->device_ = rtcNewDevice("verbose=0");
  if (rs->device_ == nullptr) {
    return Status::Error("Embree device creation failed (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  }
  rs->scene_ = rtcNewScene(rs->device_);
  rtcSetSceneBuildQuality(rs->scene_, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(rs->scene_, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(rs->device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), mesh.vertices.size()));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                3 * sizeof(unsigned), mesh.triangles.size()));
  if (vertices == nullptr || indices == nullptr) {
    rtcReleaseGeometry(geom);
    return Status::Error("Embree could not allocate buffers for " + std::to_string(mesh.triangles.size()) +
                         " triangles");
  }
  for (size_t i = 0; i < mesh.vertices.size(); ++i) std::memcpy(vertices + 3 * i, mesh.vertices[i].data(), 3 * sizeof(float));
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) indices[3 * i + k] = static_cast<unsigned>(mesh.triangles[i][k]);
  }
  rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_HIGH);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(rs->scene_, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(rs->scene_);
  if (const RTCError err = rtcGetDeviceError(rs->device_); err != RTC_ERROR_NONE) {
    return Status::Error("Embree failed to build the scene (error " + std::to_string(err) + ")");
  }
  rs->num_triangles_ = mesh.triangles.size();
  *out = std::move(rs);
  return Status::Ok();
}

int RaycastScene::nativePacketWidth() const {
  if (rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0) return 16;
  if (rtcGetDeviceProperty(device_, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED) != 0) return 8;
  return 4;
}

RaycastScene::~RaycastScene() {
  if (scene_ != nullptr) rtcReleaseScene(scene_);
  if (device_ != nullptr) rtcReleaseDevice(device_);
}

bool RaycastScene::intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_near,
                             double t_far, double* t_hit, int* triangle) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(origin.x());
  rh.ray.org_y = static_cast<float>(origin.y());
  rh.ray.org_z = static_cast<float>(origin.z());
  rh.ray.dir_x = static_cast<float>(direction.x());
  rh.ray.dir_y = static_cast<float>(direction.y());
  rh.ray.dir_z = static_cast<float>(direction.z());
  rh.ray.tnear = static_cast<float>(t_near);
  rh.ray.tfar = static_cast<float>(std::min<double>(t_far, std::numeric_limits<float>::max()));
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  *t_hit = rh.ray.tfar;
  if (triangle != nullptr) *triangle = static_cast<int>(rh.hit.primID);
  return true;
}

}  // namespace surface_nbv
