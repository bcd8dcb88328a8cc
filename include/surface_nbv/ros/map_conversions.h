// Conversions between the map core's MapUpdate and the surface_nbv/TsdfUpdate
// message of `tsdf/update`. Both directions copy faithfully, including what
// is wrong: validation is MapMirror::apply's job, so a malformed message
// reaches the mirror as a malformed update and is refused there whole.
#pragma once

#include <std_msgs/Header.h>

#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/map_update.h"

namespace surface_nbv {

void toUpdateMsg(const MapUpdate& update, const std_msgs::Header& header, surface_nbv::TsdfUpdate* msg);

void fromUpdateMsg(const surface_nbv::TsdfUpdate& msg, MapUpdate* update);

}  // namespace surface_nbv
