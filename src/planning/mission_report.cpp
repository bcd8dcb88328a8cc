#include "surface_nbv/planning/mission_report.h"

#include <filesystem>
#include <fstream>

#include "surface_nbv/util/json_writer.h"

namespace surface_nbv {

std::string missionReportJson(const MissionReport& r) {
  const MissionProgress& p = r.progress;
  const ExplorerStats& s = r.explorer;
  JsonWriter json;
  json.beginObject().value("state", p.state).value("reason", p.reason).value("message", p.message);
  json.value("flight_time_s", p.flight_time).value("max_flight_time_s", r.max_flight_time);
  json.value("path_length_m", p.path_length).value("holds", r.holds);
  json.beginObject("uav").value("x", r.uav.x()).value("y", r.uav.y()).value("z", r.uav.z()).value("yaw", r.uav.w());
  json.endObject();
  r.tally.writeJson(&json);
  json.value("ises", r.ises).value("ises_inside", r.ises_inside);
  json.value("full_recomputes", s.full_recomputes).value("local_updates", s.local_updates).value("legs", s.legs);
  json.value("leg_failures", s.leg_failures).value("budget_stops", s.budget_stops);
  json.value("lattice_legs", s.lattice_legs);
  json.value("corridor_legs", s.corridor_legs);
  json.value("roadmap_growths", s.roadmap_growths).value("roadmap_vertices", s.roadmap_vertices);
  json.value("leg_end_wait_s", r.leg_end_wait_s);
  json.value("leg_time_budget_s", r.leg_time_budget);
  json.value("blacklisted", r.blacklisted);
  if (r.scene_defaults) json.value("scene_defaults", *r.scene_defaults);
  json.endObject();
  return json.str();
}

Status writeMissionReport(const std::string& directory, const MissionReport& report) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  const std::string path = directory + "/mission_report.json";
  std::ofstream out(path);
  out << missionReportJson(report);
  return out ? Status::Ok() : Status::Error("cannot write " + path);
}

}  // namespace surface_nbv
