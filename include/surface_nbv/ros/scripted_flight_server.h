// The scripted_flight node: flies base_link along a ScriptedFlight (loops
// around a target box) and broadcasts world -> base_link on TF, standing in
// for the planner and tracker until they exist. With publish_clock it owns
// simulated time: it advances /clock by time_scale simulated seconds per wall
// second and stamps every transform with that clock.
#pragma once

#include <memory>
#include <string>

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include "surface_nbv/ros/param_reader.h"
#include "surface_nbv/sim/scripted_flight.h"

namespace surface_nbv {

struct ScriptedFlightNodeConfig {
  FlightConfig flight;
  std::string world_frame = "world";
  std::string body_frame = "base_link";
  double tf_rate = 100.0;     // Hz of wall time
  bool publish_clock = false;
  double time_scale = 1.0;    // simulated seconds per wall second
  bool loop = false;          // start over at the end instead of hovering
  double stop_after = 0.0;    // s of flight, then hover; 0 flies the whole path

  Status validate() const;
};

Status loadScriptedFlightParams(const ros::NodeHandle& priv, ScriptedFlightNodeConfig* config);

class ScriptedFlightServer {
 public:
  ScriptedFlightServer(ros::NodeHandle nh, const ScriptedFlightNodeConfig& config);

 private:
  void onTimer(const ros::WallTimerEvent& event);

  ScriptedFlightNodeConfig config_;
  ScriptedFlight flight_;
  tf2_ros::TransformBroadcaster broadcaster_;
  ros::Publisher clock_pub_;
  ros::WallTimer timer_;
  ros::WallTime wall_start_;
  ros::Time start_;
  double sim_elapsed_ = 0.0;
  bool finished_logged_ = false;
};

}  // namespace surface_nbv
