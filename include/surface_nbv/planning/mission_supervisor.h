// The mission's rules, in one place for both ways of flying one: nbv_mission
// (mission/mission_runner.h, headless) and nbv_planner (ros/nbv_planner_server.h)
// drive a MissionSupervisor and only carry its answers out.
//
//   take-off   turn start_spin in place before the first plan,
//   leg end    a leg has ended when the tracker says it is past its end
//              (headless), when leg_settle seconds have passed since its
//              reference ended (a tracker that reports nothing, ROS), or,
//              with leg_lookahead > 0, when its reference has less than that
//              left and the UAV is already at its end (flying on, Sec. 4),
//   decisions  the Explorer decides on a frontier every frontier_period
//              seconds of flight (headless) or on every new frontier the
//              driver reports (ROS), and at once when a leg with a target ends,
//   limits     the mission ends at max_flight_time or max_path_length,
//   tally      what was decided, how often, and how long it took, for the
//              mission reports.
//
// ROS-free and clock-free: the driver gives flight time, pose and path flown
// (SupervisorInput); the supervisor answers what to do. Same inputs, same map:
// same decisions.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/surface/frontier.h"
#include "surface_nbv/util/json_writer.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// The reference a mission flies its legs at and when it ends: keys of the
// mission section, read by nbv_mission and nbv_planner alike (MissionConfig
// and PlannerNodeConfig are MissionFlightConfigs), checked here once.
struct MissionFlightConfig {
  double speed = 0.5;              // reference speed [m/s] (the paper's), at most the tracker's v_max
  double yaw_rate = 1.0;           // reference yaw rate [rad/s], at most the tracker's limit
  // A leg ends (and the next is planned) once its reference has less than
  // this many seconds left and the UAV is within the explorer's
  // reach_tolerance of its end, facing its yaw to within leg_yaw_tolerance:
  // the UAV flies on instead of stopping at every viewpoint. 0: a leg ends
  // when its reference does.
  double leg_lookahead = 0.0;      // s
  double leg_yaw_tolerance = 0.35; // rad
  double max_flight_time = 0.0;    // the mission ends there [s of flight]; 0: no limit
  double start_spin = 6.2832;      // yaw turned in place before the first plan [rad]

  // Names the first bad key ("speed expected in (0, 20] m/s").
  Status validate() const;
};

struct SupervisorConfig {
  MissionFlightConfig flight;
  double reach_tolerance = 1.0;    // m: the Explorer's (ExplorerConfig::reach_tolerance)
  // > 0: the Explorer decides every this many flight seconds (the driver
  // builds the frontier when asked); 0: on each frontier the driver reports new.
  double frontier_period = 0.0;    // s
  // >= 0: a leg has also ended this long after its reference's end (for a
  // tracker that does not say when it is done); < 0: only the tracker says.
  double leg_settle = -1.0;        // s
  double max_path_length = 0.0;    // m; 0: no limit
};

// What the driver observes, each time it asks.
struct SupervisorInput {
  double t = 0.0;                  // flight seconds since the mission started
  Eigen::Vector4d uav = Eigen::Vector4d::Zero();  // [x, y, z, yaw] in the map's world
  double path_length = 0.0;        // m flown so far
  bool tracker_finished = false;   // the tracker is past the leg's end, holding its last point
  bool frontier_new = false;       // a frontier arrived since the last decision (frontier_period 0)
  bool has_target = false;         // the Explorer flies to a tour target (Explorer::hasTarget())
};

enum class SupervisorStep {
  kWait,     // nothing to decide: fly on
  kDecide,   // bring the frontier up to date and call decide()
  kDone,     // a limit ended the mission (endReason())
};

// What the mission decided and what it cost, for the reports.
struct SupervisorTally {
  size_t fly = 0, hover = 0, cont = 0, done = 0;  // decisions by action
  std::vector<double> decision_ms;               // the Explorer's wall time of each decision
  double max_decision_ms = 0.0;
  size_t legs_sent = 0, legs_dropped = 0;        // legs flown / refused or cancelled by the driver
  size_t decisions() const { return decision_ms.size(); }
  // decisions_fly ... decision_wall_s_total / median / p90 / max.
  void writeJson(JsonWriter* json) const;
};

// One call a driver made to the supervisor, as recorded (setRecording) to be
// replayed through another supervisor: same calls, same answers.
struct SupervisorCall {
  enum class Kind { kTakeOff, kLegSent, kLegDropped, kPoll, kDecided, kRecord };
  Kind kind = Kind::kPoll;
  SupervisorInput in;                 // kPoll, kDecided; kTakeOff: in.uav
  Eigen::Vector4d goal = Eigen::Vector4d::Zero();  // kLegSent
  double t_end = 0.0;                 // kLegSent
  SupervisorStep step = SupervisorStep::kWait;      // kPoll: the answer
  size_t spin = 0;                    // kTakeOff: the answer's waypoints
  ExplorerAction action = ExplorerAction::kContinue;  // kDecided, kRecord
  ReplanReason reason = ReplanReason::kNone;
  std::string message;
  double decision_ms = 0.0;
};

class MissionSupervisor {
 public:
  // `config.flight` must validate().
  explicit MissionSupervisor(const SupervisorConfig& config);

  // Take-off at `uav`: the spin's waypoints (each [x, y, z, yaw], without the
  // current pose), empty when start_spin is 0. The driver flies them as a leg
  // and reports it with legSent(); no decision is asked for before it ends.
  std::vector<Eigen::Vector4d> takeOff(const Eigen::Vector4d& uav);
  // The driver flies a leg ending at `goal` whose reference ends at flight time `t_end`.
  void legSent(const Eigen::Vector4d& goal, double t_end);
  // The driver does not fly the leg it was given (refused by the tracker,
  // held, cancelled): it has no leg whose end the rules could wait for. A
  // dropped take-off spin is over: the next poll decides.
  void legDropped();

  // The limit the mission has reached ("max_flight_time: ..."), or empty.
  std::string limitReached(double t, double path_length) const;
  // Has the current leg ended (the rules above)?
  bool legEnded(const SupervisorInput& in) const;
  // What to do now. kDecide: the driver builds or takes the frontier and calls decide().
  SupervisorStep poll(const SupervisorInput& in);
  // The Explorer's decision on `frontier`, for the input poll() was given
  // (Explorer::update, told whether the leg ended, then decided()).
  ExplorerDecision decide(Explorer* explorer, const Frontier& frontier, const SupervisorInput& in);
  // After a kDecide poll: the Explorer decided `d` (what decide() does
  // after asking it; a replay gives the recorded decisions here).
  void decided(const ExplorerDecision& d, const SupervisorInput& in);
  // Whether the leg had ended at the last poll (what decide() tells the Explorer).
  bool legEndedAtPoll() const { return leg_ended_; }
  // A decision the driver got from the Explorer itself (Explorer::checkPath
  // between frontiers), for the tally and the end of the mission.
  void record(const ExplorerDecision& d);

  bool spinning() const { return spinning_; }
  bool haveLeg() const { return have_leg_; }
  bool done() const { return done_; }
  bool completed() const { return completed_; }    // ended by "no ISE of C_ins remains"
  const std::string& endReason() const { return end_reason_; }  // "complete: ..." once done()
  const SupervisorTally& tally() const { return tally_; }
  const SupervisorConfig& config() const { return config_; }
  // Appends every call from now on to `calls` (not owned; nullptr: stop).
  void setRecording(std::vector<SupervisorCall>* calls) { recording_ = calls; }
  // A new mission (nbv_planner's ~start after DONE): the clock and tally start again.
  void reset();

 private:
  SupervisorStep nextStep(const SupervisorInput& in);
  void tallied(const ExplorerDecision& d);

  SupervisorConfig config_;
  bool have_leg_ = false, spinning_ = false, done_ = false, completed_ = false;
  Eigen::Vector4d leg_goal_ = Eigen::Vector4d::Zero();
  double leg_end_ = 0.0;
  double next_frontier_ = 0.0;
  bool leg_ended_ = false;  // at the last poll()
  std::string end_reason_;
  SupervisorTally tally_;
  std::vector<SupervisorCall>* recording_ = nullptr;
};

}  // namespace surface_nbv
