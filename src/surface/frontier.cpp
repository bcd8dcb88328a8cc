#include "surface_nbv/surface/frontier.h"

#include "surface_nbv/sim/scripted_flight.h"

namespace surface_nbv {

Transform Viewpoint::cameraPose() const {
  Transform T_W_B = Transform::Identity();
  T_W_B.translation() = position;
  T_W_B.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T_W_B * opticalInBody();
}

}  // namespace surface_nbv
