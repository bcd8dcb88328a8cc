#include "surface_nbv/sensor/camera_mount.h"

#include <cmath>

#include <Eigen/Geometry>

namespace surface_nbv {

Transform levelBodyPose(const Eigen::Vector3d& p_W, double yaw) {
  Transform T_W_B = Transform::Identity();
  T_W_B.translation() = p_W;
  T_W_B.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T_W_B;
}

Transform opticalInBody(const Eigen::Vector3d& offset, double pitch_deg) {
  Transform T_B_C = Transform::Identity();
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d(0, -1, 0);  // optical x = body right
  R.col(1) = Eigen::Vector3d(0, 0, -1);  // optical y = body down
  R.col(2) = Eigen::Vector3d(1, 0, 0);   // optical z = body forward
  // A positive turn about body y takes forward (x) towards down (-z).
  T_B_C.linear() = Eigen::AngleAxisd(pitch_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix() * R;
  T_B_C.translation() = offset;
  return T_B_C;
}

Transform opticalInBody(const CameraConfig& camera) { return opticalInBody(Eigen::Vector3d::Zero(), camera.pitch_deg); }

}  // namespace surface_nbv
