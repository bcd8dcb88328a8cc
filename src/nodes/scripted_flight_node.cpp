// scripted_flight: flies base_link around a target box on TF (and /clock).
#include <ros/ros.h>

#include "surface_nbv/ros/scripted_flight_server.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "scripted_flight");
  ros::NodeHandle nh, priv("~");
  surface_nbv::ScriptedFlightNodeConfig config;
  if (const surface_nbv::Status s = surface_nbv::loadScriptedFlightParams(priv, &config); !s) {
    ROS_FATAL("scripted_flight: bad parameter: %s", s.message().c_str());
    return 2;
  }
  surface_nbv::ScriptedFlightServer server(nh, config);
  ros::spin();
  return 0;
}
