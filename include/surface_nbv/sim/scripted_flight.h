// A scripted inspection flight for the simulator before the planner flies:
// loops around the footprint of a box at a fixed standoff (straight sides and
// quarter-circle corners), one loop per altitude, climbing between loops,
// at constant speed, yaw facing the box. Poses are of base_link in the world
// frame (x forward, z up); sensor/camera_mount.h gives the camera mount.
#pragma once

#include <vector>

#include "surface_nbv/common.h"
#include "surface_nbv/sensor/camera_mount.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct FlightConfig {
  AlignedBox target;                    // the structure to circle (its xy footprint is used)
  double standoff = 5.0;                // m, horizontal distance to the footprint
  std::vector<double> altitudes{2.0};   // m, one loop per altitude, in order
  double speed = 0.5;                   // m/s along the path

  Status validate() const;
};

// FlightConfig for `bounds` with `levels` loops spread over its height.
FlightConfig flightAround(const AlignedBox& bounds, double standoff, int levels, double speed);

class ScriptedFlight {
 public:
  explicit ScriptedFlight(const FlightConfig& config);

  double length() const { return total_length_; }                // m
  double duration() const { return total_length_ / config_.speed; }  // s
  // Pose of base_link at time t in seconds (clamped to [0, duration()]).
  Transform poseAt(double t) const;
  // Pose at arc length s in metres along the whole flight (clamped).
  Transform poseAtDistance(double s) const;

 private:
  struct Segment {
    Eigen::Vector3d start, end;   // straight or vertical segment (arc: start = corner)
    double yaw0 = 0.0, yaw1 = 0.0;  // yaw at start and end (arc: also the polar angle + pi)
    bool arc = false;
    double length = 0.0;
  };
  void addLoop(double z);

  FlightConfig config_;
  std::vector<Segment> segments_;
  double total_length_ = 0.0;
};

}  // namespace surface_nbv
