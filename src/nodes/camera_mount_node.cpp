// camera_mount: publishes the static transform base_link -> camera optical
// frame (z forward, x right, y down) of a forward-facing depth camera on a
// level UAV, pitched down by the shared camera/pitch_deg (0: level).
// Parameters: ~body_frame, ~camera_frame, ~offset [x, y, z] in base_link,
// ~shared_namespace (where camera/pitch_deg lives, /nbv by default).
#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "surface_nbv/config/config_keys.h"
#include "surface_nbv/ros/param_reader.h"
#include "surface_nbv/ros/sim_params.h"
#include "surface_nbv/sensor/camera_mount.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "camera_mount");
  ros::NodeHandle priv("~");
  std::string body_frame = "base_link", camera_frame = "camera", shared_namespace = surface_nbv::kSharedNamespace;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  surface_nbv::ParamReader reader(priv);
  reader.get("body_frame", &body_frame);
  reader.get("camera_frame", &camera_frame);
  reader.get("offset", &offset);
  reader.get("shared_namespace", &shared_namespace);
  reader.checkUnknown();
  if (const surface_nbv::Status s = reader.status(); !s || !offset.allFinite() || body_frame == camera_frame) {
    ROS_FATAL("camera_mount: bad parameter: %s", s ? "offset must be finite and frames distinct" : s.message().c_str());
    return 2;
  }
  surface_nbv::CameraConfig camera;
  surface_nbv::ParamReader shared{ros::NodeHandle(shared_namespace)};
  surface_nbv::readCameraKeys(shared, &camera);
  shared.checkUnknown("camera");
  surface_nbv::Status s = shared.status();
  if (s) s = camera.validate();
  if (!s) {
    ROS_FATAL("camera_mount: bad parameter: %s/%s", shared_namespace.c_str(), s.message().c_str());
    return 2;
  }
  geometry_msgs::TransformStamped tf = tf2::eigenToTransform(surface_nbv::opticalInBody(offset, camera.pitch_deg));
  tf.header.stamp = ros::Time(0);
  tf.header.frame_id = body_frame;
  tf.child_frame_id = camera_frame;
  tf2_ros::StaticTransformBroadcaster broadcaster;
  broadcaster.sendTransform(tf);
  ros::spin();
  return 0;
}
