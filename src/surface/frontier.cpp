#include "surface_nbv/surface/frontier.h"

#include "surface_nbv/sensor/camera_mount.h"

namespace surface_nbv {

Transform Viewpoint::cameraPose(const CameraConfig& camera) const {
  return levelBodyPose(position, yaw) * opticalInBody(camera);
}

}  // namespace surface_nbv
