// One whole exploration mission in one process, without ROS: the same core
// objects the nodes wrap, wired as the node graph wires them.
//
//   DepthRenderer (Embree) -> TsdfIntegrator -> CollisionMap -> FrontierBuilder
//   -> Explorer (Fig. 1: cluster graph, LK tour, LazyPRM* legs)
//   -> timeWaypoints at the reference speed -> TrackerSim (MPC + UAV model)
//
// Flight time advances in the tracker's fixed steps; a depth frame is rendered
// at the UAV's pose every 1 / frame_rate flight seconds, the frontier is
// rebuilt every frontier_period flight seconds and whenever a leg ends. At
// take-off the ball of start_free_radius is declared free (the camera cannot
// see closer than min range) and the UAV turns start_spin in place. The
// mission ends when the Explorer says so (no ISE of C_ins left, or nothing
// reachable) or at max_flight_time. Same config and seed: same mission.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "surface_nbv/map/mesh_layer.h"
#include "surface_nbv/map/tsdf_map.h"
#include "surface_nbv/mission/mission_config.h"
#include "surface_nbv/planning/mission_supervisor.h"
#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/sim/raycast_scene.h"

namespace surface_nbv {

// One frontier update of the mission, with what the map and plan looked like.
struct MissionEvent {
  double t = 0.0;              // flight time [s]
  double path_length = 0.0;    // flown so far [m]
  size_t ises = 0, inside = 0, remaining = 0, viewpoints = 0, clusters = 0, tour = 0;
  size_t roadmap = 0;          // the leg planner's roadmap vertices
  double observed = -1.0;      // fraction of probe points observed; -1 when not measured
  std::string action, reason;  // the Explorer's decision
  std::string message;         // ... and its message (why it hovers, what failed)
  size_t leg_failures = 0;     // legs failed so far
  Eigen::Vector4d uav = Eigen::Vector4d::Zero();  // the UAV's pose [x, y, z, yaw] at the update
  // Wall-clock milliseconds of this update: collision map, frontier, and the
  // Explorer's graph / tour / leg; full_recompute as ExplorerDecision's.
  double collision_ms = 0.0, frontier_ms = 0.0, graph_ms = 0.0, tour_ms = 0.0, path_ms = 0.0;
  bool full_recompute = false;
};

struct MissionStageTimes {  // wall-clock milliseconds, summed over the mission
  double render = 0, integrate = 0, collision = 0, frontier = 0, graph = 0, tour = 0, path = 0, tracker = 0;
  // The frontier's own stages (FrontierStats), summed: they make up `frontier`.
  double frontier_ises = 0, frontier_poses = 0, frontier_merge = 0, frontier_visibility = 0, frontier_clusters = 0;
  double total() const { return render + integrate + collision + frontier + graph + tour + path + tracker; }
};

struct MissionResult {
  Status status;                        // an error means the mission could not run
  bool completed = false;               // ended by "no ISE of C_ins remains"
  std::string end_reason;
  double flight_time = 0.0;             // s
  double path_length = 0.0;             // m
  double wall_time = 0.0;               // s
  size_t frames = 0, frontier_updates = 0;
  ExplorerStats explorer;
  size_t blacklisted = 0;
  size_t final_ises = 0, final_inside = 0;
  std::vector<Eigen::Vector4d> flown;   // pose at every frame [x, y, z, yaw]
  std::vector<double> flown_t;          // its flight time
  std::vector<MissionEvent> events;     // one per frontier update
  MissionStageTimes times;
  double max_frontier_ms = 0.0, max_plan_ms = 0.0;  // slowest single update / Explorer decision
  PoseErrorStats pose_error;            // the estimate against the truth (MissionConfig::pose_error)
  PoseErrorStats fused_pose_error;      // the poses frames were fused at against the truth
  size_t yaw_corrections = 0;           // frames whose walls corrected the heading (MissionConfig::manhattan_yaw)
  SupervisorTally tally;                // the decisions and legs, as MissionSupervisor counted them
};

class MissionRunner {
 public:
  // `config` must validate(); `scene` renders the depth (not owned).
  MissionRunner(const MissionConfig& config, const RaycastScene& scene);
  ~MissionRunner();

  // Points on the true surface: at every progress line the fraction of them
  // in observed surface voxels is measured (a cheap running coverage).
  void setProbePoints(std::vector<Eigen::Vector3d> points) { probe_ = std::move(points); }
  // Called with each event that carries a progress measurement.
  void setProgress(std::function<void(const MissionEvent&)> progress) { progress_ = std::move(progress); }

  // Every `period` seconds of flight (and at the end), with the flight time,
  // the path flown so far and the map the reconstruction is meshed from,
  // every frame up to then fused into it: for the coverage over time. The
  // mission is the same with or without; its wall time includes the calls.
  using Checkpoint = std::function<void(double t, double path_length, const TsdfMap& mesh_map)>;
  void setCheckpoints(double period, Checkpoint checkpoint) {
    checkpoint_period_ = period, checkpoint_ = std::move(checkpoint);
  }

  // Diagnostic: the explorer's head_lookahead ranks targets by the ground
  // truth's unobserved probe points in view (oracle_gain.h) instead of |C_q|.
  void setOracleGain(bool on) { oracle_gain_ = on; }

  // Every call the mission makes to its MissionSupervisor is appended to
  // `calls` (not owned), to be replayed (test_mission_supervisor).
  void setSupervisorRecording(std::vector<SupervisorCall>* calls) { recording_ = calls; }

  MissionResult run();
  // The map after run().
  const TsdfMap& map() const;
  // The map the reconstruction is meshed from after run(): the mesh layer
  // (TsdfConfig::mesh_truncation, mesh_layer.h), else map().
  const TsdfMap& meshMap() const;

 private:
  double observedFraction() const;

  MissionConfig config_;
  const RaycastScene& scene_;
  std::unique_ptr<TsdfMap> map_;
  std::unique_ptr<MeshLayer> mesh_layer_;
  std::vector<Eigen::Vector3d> probe_;
  std::function<void(const MissionEvent&)> progress_;
  bool oracle_gain_ = false;
  double checkpoint_period_ = 0.0;
  Checkpoint checkpoint_;
  std::vector<SupervisorCall>* recording_ = nullptr;
};

}  // namespace surface_nbv
