#include "surface_nbv/ros/planner_params.h"

#include <cmath>
#include <limits>

#include "surface_nbv/ros/mapper_params.h"
#include "surface_nbv/ros/sim_params.h"
#include "surface_nbv/tracking/uav_model.h"

namespace surface_nbv {

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
  if (!std::isfinite(speed) || speed <= 0.0 || speed > 20.0) return Status::Error("speed expected in (0, 20] m/s");
  if (!std::isfinite(yaw_rate) || yaw_rate <= 0.0 || yaw_rate > 10.0) {
    return Status::Error("yaw_rate expected in (0, 10] rad/s");
  }
  if (!std::isfinite(trajectory_spacing) || trajectory_spacing <= 0.0) {
    return Status::Error("trajectory_spacing expected > 0");
  }
  if (!(leg_lookahead >= 0.0) || leg_lookahead > 60.0) return Status::Error("leg_lookahead expected in [0, 60] s");
  if (!(leg_yaw_tolerance > 0.0) || leg_yaw_tolerance > M_PI) {
    return Status::Error("leg_yaw_tolerance expected in (0, pi] rad");
  }
  if (!(leg_restart_reach >= 0.0) || leg_restart_reach > 50.0) {
    return Status::Error("leg_restart_reach expected in [0, 50] m (0: off)");
  }
  if (!(max_tracking_error >= 0.0) || !std::isfinite(max_tracking_error)) {
    return Status::Error("max_tracking_error expected >= 0 m (0: off)");
  }
  if (!(off_track_time > 0.0) || !std::isfinite(off_track_time)) return Status::Error("off_track_time expected > 0 s");
  if (!(start_spin >= 0.0) || start_spin > 20.0) return Status::Error("start_spin expected in [0, 20] rad");
  if (!(leg_settle >= 0.0) || leg_settle > 60.0) return Status::Error("leg_settle expected in [0, 60] s");
  if (!(odometry_timeout > 0.0) || !std::isfinite(odometry_timeout)) return Status::Error("odometry_timeout expected > 0");
  if (!(map_timeout > 0.0) || !std::isfinite(map_timeout)) return Status::Error("map_timeout expected > 0");
  if (!(max_flight_time >= 0.0) || !std::isfinite(max_flight_time)) {
    return Status::Error("max_flight_time expected >= 0 s (0: no limit)");
  }
  if (Status s = feed.validate(); !s) return s;
  if (!std::isfinite(stats_period) || stats_period <= 0.0) return Status::Error("stats_period expected > 0");
  return Status::Ok();
}

namespace {

// The explorer's keys, as the mission section of the scene's YAML names them
// (nbv_mission reads the same section) and as private parameters. An
// unknown tour_objective is an error naming the key.
Status readExplorerKeys(ParamReader* r, ExplorerConfig* e) {
  r->get("match_radius", &e->match_radius);
  r->get("reach_tolerance", &e->reach_tolerance);
  r->get("max_failures", &e->max_failures);
  r->get("max_visits", &e->max_visits);
  r->get("blacklist_radius", &e->blacklist_radius);
  r->get("always_full", &e->always_full);
  r->get("full_on_leg_end", &e->full_on_leg_end);
  r->get("travel_yaw", &e->travel_yaw);
  r->get("turn_distance", &e->turn_distance);
  r->get("turn_lead", &e->turn_lead);
  r->get("min_visible", &e->min_visible);
  r->get("head_lookahead", &e->head_lookahead);
  r->get("head_unknown", &e->head_unknown);
  r->get("head_lambda", &e->head_lambda);
  r->get("head_vertical_scale", &e->head_vertical_scale);
  r->get("gaze", &e->gaze.enabled);
  r->get("gaze_step", &e->gaze.step);
  r->get("gaze_min_ises", &e->gaze.min_ises);
  r->get("pool_unknown_below", &e->pool_unknown_below);
  r->get("max_leg_attempts", &e->max_leg_attempts);
  r->get("leg_time_budget", &e->leg_time_budget);
  r->get("path_distances", &e->path_distances);
  r->get("check_reachable", &e->check_reachable);
  r->get("reach_clearance", &e->reach_clearance);
  r->get("empty_updates_before_done", &e->empty_updates_before_done);
  std::string objective = toString(e->graph.objective);
  r->get("tour_objective", &objective);
  if (!parseTourObjective(objective, &e->graph.objective)) {
    return Status::Error(r->ns() + "/tour_objective expected 'product' or 'sum'");
  }
  return Status::Ok();
}

}  // namespace

Status loadPlannerParams(const ros::NodeHandle& priv, PlannerNodeConfig* c) {
  ParamReader reader(priv);
  reader.get("shared_namespace", &c->shared_namespace);
  reader.get("mission_namespace", &c->mission_namespace);
  // The mission section first (the same settings as the headless runner),
  // then the node's own parameters over it.
  ParamReader mission((ros::NodeHandle(c->mission_namespace)));
  if (Status st = readExplorerKeys(&mission, &c->explorer); !st) return st;
  mission.get("path_iterations", &c->path.iteration_budget);
  mission.get("path_time_budget", &c->path.time_budget);
  mission.get("path_lattice_step", &c->path.lattice_step);
  int lattice_nodes = static_cast<int>(c->path.lattice_max_nodes);
  mission.get("path_lattice_nodes", &lattice_nodes);
  c->path.lattice_max_nodes = lattice_nodes > 0 ? static_cast<size_t>(lattice_nodes) : 0;
  mission.get("speed", &c->speed);
  mission.get("yaw_rate", &c->yaw_rate);
  mission.get("leg_lookahead", &c->leg_lookahead);
  mission.get("leg_yaw_tolerance", &c->leg_yaw_tolerance);
  mission.get("max_flight_time", &c->max_flight_time);
  if (Status st = mission.status(); !st) return st;
  if (!(c->max_flight_time >= 0.0) || !std::isfinite(c->max_flight_time)) {
    return Status::Error(mission.ns() + "/max_flight_time expected >= 0 s (0: no limit)");
  }
  if (Status st = readExplorerKeys(&reader, &c->explorer); !st) return st;
  reader.get("world_frame", &c->world_frame);
  reader.get("replan_rate", &c->replan_rate);
  reader.get("prompt_ticks", &c->prompt_ticks);
  reader.get("speed", &c->speed);
  reader.get("yaw_rate", &c->yaw_rate);
  reader.get("trajectory_spacing", &c->trajectory_spacing);
  reader.get("start_spin", &c->start_spin);
  reader.get("leg_settle", &c->leg_settle);
  reader.get("leg_lookahead", &c->leg_lookahead);
  reader.get("leg_yaw_tolerance", &c->leg_yaw_tolerance);
  reader.get("leg_restart_reach", &c->leg_restart_reach);
  reader.get("max_tracking_error", &c->max_tracking_error);
  reader.get("off_track_time", &c->off_track_time);
  reader.get("odometry_timeout", &c->odometry_timeout);
  reader.get("map_timeout", &c->map_timeout);
  reader.get("max_flight_time", &c->max_flight_time);
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
  std::string tracker_namespace = kTrackerNamespace;
  reader.get("tracker_namespace", &tracker_namespace);
  reader.checkUnknown();
  if (Status st = reader.status(); !st) return st;

  ParamReader shared(ros::NodeHandle(c->shared_namespace));
  readSharedMapConfig(&shared, &c->map);
  shared.get("lambda_tc", &c->explorer.graph.lambda_tc);
  shared.get("lambda_ic", &c->explorer.graph.lambda_ic);
  readCameraConfig(&shared, &c->explorer.gaze.camera);  // the gaze looks with the shared camera
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
