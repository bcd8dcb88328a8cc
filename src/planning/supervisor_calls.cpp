#include "surface_nbv/planning/supervisor_calls.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace surface_nbv {

namespace {

constexpr char kHeader[] =
    "kind,t,x,y,z,yaw,path_length,tracker_finished,frontier_new,has_target,goal_x,goal_y,goal_z,goal_yaw,t_end,step,"
    "spin,action,reason,decision_ms,message";
constexpr size_t kNumbered = 20;  // the columns before the message

// The value of `E` whose toString() is `name`: enums here are small and
// toString() says "unknown" past their last value.
template <typename E>
bool fromName(const std::string& name, E* value) {
  if (name == "unknown") return false;
  for (int i = 0; i < 64; ++i) {
    if (name == toString(static_cast<E>(i))) {
      *value = static_cast<E>(i);
      return true;
    }
  }
  return false;
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

bool parseNumber(const std::string& s, double* v) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  *v = std::strtod(s.c_str(), &end);
  return errno == 0 && end == s.c_str() + s.size();
}

bool parseFlag(const std::string& s, bool* v) {
  if (s != "0" && s != "1") return false;
  *v = s == "1";
  return true;
}

Status parseRow(const std::string& line, SupervisorCall* c) {
  std::vector<std::string> f;
  size_t start = 0;
  while (f.size() < kNumbered) {
    const size_t comma = line.find(',', start);
    if (comma == std::string::npos) return Status::Error("expected 21 columns");
    f.push_back(line.substr(start, comma - start));
    start = comma + 1;
  }
  c->message = line.substr(start);
  if (!fromName(f[0], &c->kind)) return Status::Error("unknown kind '" + f[0] + "'");
  double* numbers[] = {&c->in.t,    &c->in.uav.x(), &c->in.uav.y(), &c->in.uav.z(), &c->in.uav.w(), &c->in.path_length};
  for (size_t i = 0; i < 6; ++i) {
    if (!parseNumber(f[1 + i], numbers[i])) return Status::Error("column " + std::to_string(2 + i) + " is not a number");
  }
  bool* flags[] = {&c->in.tracker_finished, &c->in.frontier_new, &c->in.has_target};
  for (size_t i = 0; i < 3; ++i) {
    if (!parseFlag(f[7 + i], flags[i])) return Status::Error("column " + std::to_string(8 + i) + " expected 0 or 1");
  }
  double* goal[] = {&c->goal.x(), &c->goal.y(), &c->goal.z(), &c->goal.w(), &c->t_end};
  for (size_t i = 0; i < 5; ++i) {
    if (!parseNumber(f[10 + i], goal[i])) return Status::Error("column " + std::to_string(11 + i) + " is not a number");
  }
  if (!fromName(f[15], &c->step)) return Status::Error("unknown step '" + f[15] + "'");
  double spin = 0.0;
  if (!parseNumber(f[16], &spin) || spin < 0.0 || spin != static_cast<double>(static_cast<size_t>(spin))) {
    return Status::Error("spin expected a count");
  }
  c->spin = static_cast<size_t>(spin);
  if (!fromName(f[17], &c->action)) return Status::Error("unknown action '" + f[17] + "'");
  if (!fromName(f[18], &c->reason)) return Status::Error("unknown reason '" + f[18] + "'");
  if (!parseNumber(f[19], &c->decision_ms)) return Status::Error("decision_ms is not a number");
  return Status::Ok();
}

ExplorerDecision recordedDecision(const SupervisorCall& c) {
  ExplorerDecision d;
  d.action = c.action;
  d.reason = c.reason;
  d.message = c.message;
  d.timings.total_ms = c.decision_ms;
  return d;
}

}  // namespace

const char* toString(SupervisorCall::Kind kind) {
  switch (kind) {
    case SupervisorCall::Kind::kTakeOff: return "take_off";
    case SupervisorCall::Kind::kLegSent: return "leg_sent";
    case SupervisorCall::Kind::kLegDropped: return "leg_dropped";
    case SupervisorCall::Kind::kPoll: return "poll";
    case SupervisorCall::Kind::kDecided: return "decided";
    case SupervisorCall::Kind::kRecord: return "record";
  }
  return "unknown";
}

const char* toString(SupervisorStep step) {
  switch (step) {
    case SupervisorStep::kWait: return "wait";
    case SupervisorStep::kDecide: return "decide";
    case SupervisorStep::kDone: return "done";
  }
  return "unknown";
}

Status writeSupervisorCalls(const std::string& path, const std::vector<SupervisorCall>& calls) {
  std::ofstream out(path);
  if (!out) return Status::Error("cannot write " + path);
  out << kHeader << '\n';
  for (const SupervisorCall& c : calls) {
    out << toString(c.kind);
    for (double v : {c.in.t, c.in.uav.x(), c.in.uav.y(), c.in.uav.z(), c.in.uav.w(), c.in.path_length}) {
      out << ',' << number(v);
    }
    for (bool b : {c.in.tracker_finished, c.in.frontier_new, c.in.has_target}) out << ',' << (b ? '1' : '0');
    for (double v : {c.goal.x(), c.goal.y(), c.goal.z(), c.goal.w(), c.t_end}) out << ',' << number(v);
    out << ',' << toString(c.step) << ',' << c.spin << ',' << toString(c.action) << ',' << toString(c.reason) << ','
        << number(c.decision_ms) << ',';
    for (char ch : c.message) out << (ch == '\n' || ch == '\r' ? ' ' : ch);
    out << '\n';
  }
  out.flush();
  return out ? Status::Ok() : Status::Error("cannot write " + path);
}

Status readSupervisorCalls(const std::string& path, std::vector<SupervisorCall>* calls) {
  std::ifstream in(path);
  if (!in) return Status::Error("cannot read " + path);
  std::string line;
  if (!std::getline(in, line) || line != kHeader) return Status::Error(path + ": line 1: expected the header " + kHeader);
  std::vector<SupervisorCall> read;
  for (size_t n = 2; std::getline(in, line); ++n) {
    SupervisorCall c;
    if (Status s = parseRow(line, &c); !s) return Status::Error(path + ": line " + std::to_string(n) + ": " + s.message());
    read.push_back(std::move(c));
  }
  *calls = std::move(read);
  return Status::Ok();
}

Status replaySupervisorCalls(const std::vector<SupervisorCall>& calls, MissionSupervisor* supervisor) {
  for (size_t i = 0; i < calls.size(); ++i) {
    const SupervisorCall& c = calls[i];
    const std::string where = "call " + std::to_string(i) + " (" + toString(c.kind) + " at t = " + number(c.in.t) + ")";
    switch (c.kind) {
      case SupervisorCall::Kind::kTakeOff:
        if (const size_t spin = supervisor->takeOff(c.in.uav).size(); spin != c.spin) {
          return Status::Error(where + ": a spin of " + std::to_string(spin) + " waypoints, recorded " +
                               std::to_string(c.spin));
        }
        break;
      case SupervisorCall::Kind::kLegSent: supervisor->legSent(c.goal, c.t_end); break;
      case SupervisorCall::Kind::kLegDropped: supervisor->legDropped(); break;
      case SupervisorCall::Kind::kPoll:
        if (const SupervisorStep step = supervisor->poll(c.in); step != c.step) {
          return Status::Error(where + ": " + toString(step) + ", recorded " + toString(c.step));
        }
        break;
      case SupervisorCall::Kind::kDecided: supervisor->decided(recordedDecision(c), c.in); break;
      case SupervisorCall::Kind::kRecord: supervisor->record(recordedDecision(c)); break;
    }
  }
  return Status::Ok();
}

}  // namespace surface_nbv
