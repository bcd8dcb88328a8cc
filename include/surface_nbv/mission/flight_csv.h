// The flown path's file, nbv_mission's trial_K/path.csv: header
// t_s,x_m,y_m,z_m,yaw_rad, then one base_link pose in the world frame per
// integrated depth frame. nbv_mission and nbv_oracle write it; nbv_refuse
// reads it and renders the poses again, so they keep 10 significant digits.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/util/status.h"

namespace surface_nbv {

constexpr const char* kFlightCsvHeader = "t_s,x_m,y_m,z_m,yaw_rad";

// Writes t[i] and poses[i] ([x, y, z, yaw]) row by row; t and poses have the
// same length. Error naming the file when it cannot be written.
Status writeFlightCsv(const std::string& file, const std::vector<double>& t,
                      const std::vector<Eigen::Vector4d>& poses);

}  // namespace surface_nbv
