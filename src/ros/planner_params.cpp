#include "surface_nbv/ros/planner_params.h"

#include <cmath>
#include <limits>

#include "surface_nbv/ros/mapper_params.h"
#include "surface_nbv/ros/mission_params.h"
#include "surface_nbv/ros/sim_params.h"
#include "surface_nbv/tracking/uav_model.h"

namespace surface_nbv {

SupervisorConfig PlannerNodeConfig::supervisorConfig() const {
  SupervisorConfig rules;
  rules.flight = *this;
  rules.reach_tolerance = explorer.reach_tolerance;
  rules.frontier_period = 0.0;
  rules.leg_settle = leg_settle;
  return rules;
}

Status PlannerNodeConfig::validate() const {
  if (Status s = map.validate(); !s) return s;
  if (Status s = explorer.validate(); !s) return s;
  if (Status s = path.validate(); !s) return s;
  if (Status s = collision.validate(); !s) return s;
  if (path.collision_radius >= collision.max_distance) {
    return Status::Error("collision_radius expected < collision_max_distance");
  }
  if (world_frame.empty()) return Status::Error("world_frame expected a frame name");
  if (!std::isfinite(replan_rate) || replan_rate <= 0.0 || replan_rate > 50.0) {
    return Status::Error("replan_rate expected in (0, 50] Hz");
  }
  if (Status s = MissionFlightConfig::validate(); !s) return s;
  if (!std::isfinite(trajectory_spacing) || trajectory_spacing <= 0.0) {
    return Status::Error("trajectory_spacing expected > 0");
  }
  if (!(leg_restart_reach >= 0.0) || leg_restart_reach > 50.0) {
    return Status::Error("leg_restart_reach expected in [0, 50] m (0: off)");
  }
  if (!(max_tracking_error >= 0.0) || !std::isfinite(max_tracking_error)) {
    return Status::Error("max_tracking_error expected >= 0 m (0: off)");
  }
  if (!(off_track_time > 0.0) || !std::isfinite(off_track_time)) return Status::Error("off_track_time expected > 0 s");
  if (!(leg_settle >= 0.0) || leg_settle > 60.0) return Status::Error("leg_settle expected in [0, 60] s");
  if (!(odometry_timeout > 0.0) || !std::isfinite(odometry_timeout)) return Status::Error("odometry_timeout expected > 0");
  if (!(map_timeout > 0.0) || !std::isfinite(map_timeout)) return Status::Error("map_timeout expected > 0");
  if (Status s = feed.validate(); !s) return s;
  if (!std::isfinite(stats_period) || stats_period <= 0.0) return Status::Error("stats_period expected > 0");
  return Status::Ok();
}

Status loadPlannerParams(const ros::NodeHandle& priv, PlannerNodeConfig* c) {
  ParamReader reader(priv);
  reader.get("shared_namespace", &c->shared_namespace);
  reader.get("mission_namespace", &c->mission_namespace);
  std::string tracker_namespace = kTrackerNamespace;
  reader.get("tracker_namespace", &tracker_namespace);
  // The mission section first (the same settings as the headless runner),
  // then the node's own parameters over it.
  // A mission section (the launch loads the YAML's into mission_namespace)
  // is read and checked whole as nbv_mission reads it: a file nbv_mission
  // refuses, the planner refuses, with the same reason.
  // With a mission section the flight-time limit defaults to nbv_mission's.
  if (ros::param::has(c->mission_namespace)) {
    if (Status st = loadMissionParams(c->shared_namespace, c->mission_namespace, tracker_namespace, nullptr); !st) return st;
    c->max_flight_time = MissionConfig().max_flight_time;
  }
  ParamReader mission((ros::NodeHandle(c->mission_namespace)));
  readExplorerKeys(mission, &c->explorer);
  readPathKeys(mission, &c->path);
  readFlightKeys(mission, c);
  mission.get("collision_radius", &c->path.collision_radius);
  if (Status st = mission.status(); !st) return st;
  readExplorerKeys(reader, &c->explorer);
  reader.get("world_frame", &c->world_frame);
  reader.get("replan_rate", &c->replan_rate);
  reader.get("prompt_ticks", &c->prompt_ticks);
  readFlightKeys(reader, c);
  reader.get("trajectory_spacing", &c->trajectory_spacing);
  reader.get("leg_settle", &c->leg_settle);
  reader.get("leg_restart_reach", &c->leg_restart_reach);
  reader.get("max_tracking_error", &c->max_tracking_error);
  reader.get("off_track_time", &c->off_track_time);
  reader.get("odometry_timeout", &c->odometry_timeout);
  reader.get("map_timeout", &c->map_timeout);
  reader.get("report_directory", &c->report_directory);
  reader.get("exit_when_done", &c->exit_when_done);
  reader.get("save_map_service", &c->save_map_service);
  reader.get("export_mesh_service", &c->export_mesh_service);
  reader.get("iteration_budget", &c->path.iteration_budget);
  reader.get("start_running", &c->start_running);
  reader.get("collision_radius", &c->path.collision_radius);
  reader.get("time_budget", &c->path.time_budget);
  reader.get("lattice_step", &c->path.lattice_step);
  int seed = static_cast<int>(c->path.seed);
  reader.get("seed", &seed);
  if (seed < 0) return Status::Error(priv.getNamespace() + "/seed expected >= 0");
  c->path.seed = static_cast<unsigned int>(seed);
  reader.get("collision_max_distance", &c->collision.max_distance);
  reader.get("collision_cell_size", &c->collision.min_cell_size);
  readMapFeedKeys(&reader, &c->feed);
  reader.get("stats_period", &c->stats_period);
  reader.checkUnknown();
  if (Status st = reader.status(); !st) return st;

  ParamReader shared(ros::NodeHandle(c->shared_namespace));
  readTsdfKeys(shared, &c->map);
  readUtilityKeys(shared, &c->explorer.graph);
  readCameraKeys(shared, &c->explorer.gaze.camera);  // the gaze looks with the shared camera
  if (Status st = shared.status(); !st) return st;
  if (Status st = c->validate(); !st) return Status::Error(priv.getNamespace() + "/" + st.message());
  // With the simulated UAV's limits on the server (the config's tracker
  // section), legs timed faster than it can fly are refused, as nbv_mission
  // refuses them; a stack without that section is not checked.
  double v_max = 0.0, yaw_rate_max = 0.0;
  if (!ros::param::get(tracker_namespace + "/v_max", v_max)) v_max = std::numeric_limits<double>::infinity();
  if (!ros::param::get(tracker_namespace + "/yaw_rate_max", yaw_rate_max)) {
    yaw_rate_max = std::numeric_limits<double>::infinity();
  }
  return checkReferenceWithinLimits(c->speed, c->yaw_rate, v_max, yaw_rate_max, priv.getNamespace() + "/",
                                    tracker_namespace + "/");
}

}  // namespace surface_nbv
