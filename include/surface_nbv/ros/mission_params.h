// The mission's config (mission/mission_config.h) read from the namespaces
// the launch loads the YAML file into (shared "/nbv", "/depth_sim",
// "/tracker", mission "/mission") with the readers nbv_mission uses on the
// file, and checked by MissionConfig::validate(): nbv_planner refuses what
// nbv_mission refuses, with the same reason.
#pragma once

#include <string>

#include "surface_nbv/mission/mission_config.h"

namespace surface_nbv {

// `config` may be null (check only). The tracker section from
// `tracker_namespace` (nbv_planner's ~tracker_namespace, "/tracker").
Status loadMissionParams(const std::string& shared_namespace, const std::string& mission_namespace,
                         const std::string& tracker_namespace, MissionConfig* config);

}  // namespace surface_nbv
