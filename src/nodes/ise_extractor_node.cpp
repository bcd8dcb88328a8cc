// ise_extractor: incomplete surface elements, viewpoints and clusters of the mirrored map.
#include <ros/ros.h>

#include "surface_nbv/ros/ise_extractor_server.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "ise_extractor");
  ros::NodeHandle nh, priv("~");
  surface_nbv::ExtractorConfig config;
  if (const surface_nbv::Status s = surface_nbv::loadExtractorParams(priv, &config); !s) {
    ROS_FATAL("ise_extractor: bad parameter: %s", s.message().c_str());
    return 2;
  }
  surface_nbv::IseExtractorServer server(nh, config);
  ros::spin();
  return 0;
}
