// mpc_tracker: the simulated UAV, tracking planner/trajectory with a linear MPC.
#include <ros/ros.h>

#include "surface_nbv/ros/mpc_tracker_server.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "mpc_tracker");
  ros::NodeHandle nh, priv("~");
  surface_nbv::TrackerNodeConfig config;
  if (const surface_nbv::Status s = surface_nbv::loadTrackerParams(priv, &config); !s) {
    ROS_FATAL("mpc_tracker: bad parameter: %s", s.message().c_str());
    return 2;
  }
  surface_nbv::MpcTrackerServer server(nh, config);
  ros::spin();
  return 0;
}
