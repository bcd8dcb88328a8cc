#include "surface_nbv/ros/mission_params.h"

#include "surface_nbv/ros/param_reader.h"

namespace surface_nbv {

Status loadMissionParams(const std::string& shared_namespace, const std::string& mission_namespace,
                         const std::string& tracker_namespace, MissionConfig* config) {
  ParamReader nbv{ros::NodeHandle(shared_namespace)};
  ParamReader sim{ros::NodeHandle("/depth_sim")};
  ParamReader trk{ros::NodeHandle(tracker_namespace)};
  ParamReader mission{ros::NodeHandle(mission_namespace)};
  MissionConfig c;
  if (Status s = loadMissionConfigFrom(nbv, sim, trk, mission, &c); !s) return Status::Error("mission config: " + s.message());
  if (Status s = c.validate(); !s) return Status::Error("mission config: " + s.message());
  if (config != nullptr) *config = c;
  return Status::Ok();
}

}  // namespace surface_nbv
