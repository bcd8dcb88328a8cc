// tsdf_mapper: fuses depth into the TSDF map and publishes its updates.
#include <ros/ros.h>

#include <sys/stat.h>

#include "surface_nbv/ros/tsdf_mapper_server.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "tsdf_mapper");
  ros::NodeHandle nh, priv("~");
  surface_nbv::MapperConfig config;
  if (const surface_nbv::Status s = surface_nbv::loadMapperParams(priv, &config); !s) {
    ROS_FATAL("tsdf_mapper: bad parameter: %s", s.message().c_str());
    return 2;
  }
  mkdir(config.map_directory.c_str(), 0755);
  surface_nbv::TsdfMapperServer server(nh, priv, config);
  ros::spin();
  return 0;
}
