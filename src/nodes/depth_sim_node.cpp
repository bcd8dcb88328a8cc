// depth_sim: renders depth images of a scene at the camera pose from TF.
#include <ros/ros.h>

#include "surface_nbv/ros/depth_sim_server.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "depth_sim");
  ros::NodeHandle nh, priv("~");
  surface_nbv::CameraConfig camera;
  surface_nbv::DepthSimConfig config;
  if (const surface_nbv::Status s = surface_nbv::loadDepthSimParams(priv, &camera, &config); !s) {
    ROS_FATAL("depth_sim: bad parameter: %s", s.message().c_str());
    return 2;
  }
  surface_nbv::DepthSimServer server(nh, priv, camera, config);
  if (!server.status()) {
    ROS_FATAL("depth_sim: %s", server.status().message().c_str());
    return 1;
  }
  ros::spin();
  return 0;
}
