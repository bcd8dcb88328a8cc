// nbv_planner: the cluster tour over the frontier and the PRM path to fly it.
#include <ros/ros.h>

#include "surface_nbv/ros/nbv_planner_server.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "nbv_planner");
  ros::NodeHandle nh, priv("~");
  surface_nbv::PlannerNodeConfig config;
  if (const surface_nbv::Status s = surface_nbv::loadPlannerParams(priv, &config); !s) {
    ROS_FATAL("nbv_planner: bad parameter: %s", s.message().c_str());
    return 2;
  }
  surface_nbv::NbvPlannerServer server(nh, priv, config);
  ros::spin();
  return 0;
}
