// The depth_sim node: at the camera rate it looks up world -> camera at the
// frame time (sim time under use_sim_time), renders the scene with Embree and
// publishes depth/image (32FC1), depth/camera_info, optionally depth/points,
// plus a latched ground-truth mesh marker (~ground_truth), a latched
// LINE_LIST of the camera's view frustum in the camera frame (~frustum: apex
// to near plane at min_range, near to far plane at max_range) and ~stats.
// A missing or invalid transform drops the frame (counted, throttled warning):
// nothing is ever rendered from a stale pose. ~export_scene writes the scene
// mesh (.ply or .stl) under a plain file name inside ~export_directory; paths,
// hidden names and symbolic links are refused (code 1) and nothing is written.
#pragma once

#include <memory>

#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "surface_nbv/FilePath.h"
#include "surface_nbv/ros/sim_params.h"
#include "surface_nbv/ros/stats_reporter.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/raycast_scene.h"

namespace surface_nbv {

class DepthSimServer {
 public:
  // Creates ~export_directory if missing, loads the scene and builds the BVH.
  // Check status() before spinning.
  DepthSimServer(ros::NodeHandle nh, ros::NodeHandle priv, const CameraConfig& camera, const DepthSimConfig& config);
  const Status& status() const { return status_; }

 private:
  void onTimer(const ros::TimerEvent& event);
  bool lookupPose(const ros::Time& stamp, Transform* T_W_C);
  bool exportScene(surface_nbv::FilePath::Request& req, surface_nbv::FilePath::Response& res);

  ros::NodeHandle nh_, priv_;
  DepthCamera camera_;
  DepthSimConfig config_;
  Status status_;
  TriangleMesh mesh_;
  std::unique_ptr<RaycastScene> scene_;
  std::unique_ptr<DepthRenderer> renderer_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  ros::Publisher image_pub_, info_pub_, points_pub_, mesh_pub_, frustum_pub_;
  ros::ServiceServer export_srv_;
  ros::Timer timer_;
  StatsReporter stats_;
  ros::Time last_stamp_;
  uint64_t frame_index_ = 0;
  PoseErrorModel pose_error_;
};

}  // namespace surface_nbv
