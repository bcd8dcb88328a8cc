// A mission's calls to its MissionSupervisor (SupervisorCall, recorded with
// MissionSupervisor::setRecording) as a CSV file, and their replay.
//
// nbv_planner writes supervisor_calls.csv beside mission_report.json, and
// test_mission_node replays it through a supervisor built from the
// planner's own parameters, and test_supervisor_replay does the same with a
// headless mission's calls: both drivers take the answers of the one set of
// rules, and no others.
//
// One row per call, a header first:
//   kind,t,x,y,z,yaw,path_length,tracker_finished,frontier_new,has_target,
//   goal_x,goal_y,goal_z,goal_yaw,t_end,step,spin,action,reason,decision_ms,message
// kind: take_off, leg_sent, leg_dropped, poll, decided, record; step: wait,
// decide, done; action and reason by their toString() names; numbers with 17
// significant digits, so a file reads back to the calls it was written from.
// The message is the last column and may hold commas; line breaks in it are
// written as spaces.
#pragma once

#include <string>
#include <vector>

#include "surface_nbv/planning/mission_supervisor.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

const char* toString(SupervisorCall::Kind kind);
const char* toString(SupervisorStep step);

Status writeSupervisorCalls(const std::string& path, const std::vector<SupervisorCall>& calls);
// Replaces `calls` with the file's; names the first bad line ("line 12: ...").
Status readSupervisorCalls(const std::string& path, std::vector<SupervisorCall>* calls);

// Makes each of `calls` on `supervisor` (new, or reset(), with the rules to
// check), the recorded decisions given back through decided() and record().
// An error names the first call whose answer differs from the recorded one:
// a poll's step, or a take-off spin that is there or not. The tally and end
// are then the supervisor's, to compare with the mission's report.
Status replaySupervisorCalls(const std::vector<SupervisorCall>& calls, MissionSupervisor* supervisor);

}  // namespace surface_nbv
