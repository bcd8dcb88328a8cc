// Where the flight time goes: a flown trajectory (the mission's pose at every
// frame and its flight time) split into cruising, slower moving, turning in
// place and standing still. Each interval between two consecutive samples is
// classified by its average speed and its yaw rate (the wrapped yaw change
// over the interval's duration). Units: metres, seconds, radians.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace surface_nbv {

struct FlightProfile {
  double flight_s = 0;            // summed duration of the classified intervals
  double cruise_s = 0;            // speed >= cruise_fraction * reference speed
  double moving_s = 0;            // slow_speed <= speed < cruise_fraction * reference speed
  double turning_in_place_s = 0;  // speed < slow_speed and |yaw rate| > turn_rate
  double stopped_s = 0;           // speed < slow_speed and |yaw rate| <= turn_rate
  double vertical_s = 0;          // the part of cruise_s and moving_s with |vz| > |vxy| (a subset, not a fifth class)
  double total_yaw_rad = 0;       // sum of |wrapped yaw change| over all classified intervals
  double path_m = 0;              // sum of the straight-line distances of the classified intervals
  size_t samples = 0;             // intervals classified
};

// The profile of poses [x, y, z, yaw] flown at `times` [s]. cruise_s +
// moving_s + turning_in_place_s + stopped_s == flight_s. An interval whose
// duration is not positive, or with a non-finite time or pose at either end,
// is skipped; with mismatched sizes only the common prefix is used; fewer than
// two samples give all zeros.
FlightProfile profileFlight(const std::vector<Eigen::Vector4d>& poses, const std::vector<double>& times,
                            double reference_speed, double slow_speed = 0.2, double cruise_fraction = 0.88,
                            double turn_rate = 0.3);

}  // namespace surface_nbv
