// nbv_oracle: the offline oracle reference for the exploration path (issue
// #8). Knowing the ground-truth mesh, it covers the visible surface with a
// greedy set of collision-free viewpoints and tours them with the planner's
// solver and roadmap (see oracle_planner.h); the online planner's path length
// and flight time are then reported as ratios to the oracle's.
//
//   nbv_oracle --scene plant|statue|FILE [--config YAML] [--seed S] [--out DIR]
//              [--threads N] [--target-spacing M] [--candidate-spacing M] [--max-candidates N]
//              [--path-iterations N] [--cover-fraction F]
//              [--online-path M] [--online-min MIN]
//
// Writes DIR/oracle.json, oracle.md, oracle_path.csv and oracle_uncoverable.csv
// (the targets no candidate sees; default DIR: output/oracle_<scene>), and
// oracle_flight.csv: the path timed at the mission's speed and yaw rate and
// sampled at its frame rate, in nbv_mission's path.csv format, so that
// `nbv_refuse --path DIR/oracle_flight.csv` fuses and evaluates the oracle's
// flight as a mission's. --cover-fraction (0.99 by default) stops the greedy
// cover at that share of the coverable targets: a shorter oracle flight.
// With --online-path / --online-min (an nbv_mission trial's figures) the
// ratios online / oracle are printed and written too.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "surface_nbv/mission/flight_csv.h"
#include "surface_nbv/mission/oracle_planner.h"
#include "surface_nbv/mission/scene_defaults.h"
#include "surface_nbv/util/cli_args.h"
#include "surface_nbv/util/json_writer.h"

using namespace surface_nbv;

namespace {

const char* kUsage =
    "usage: nbv_oracle --scene plant|statue|FILE [--config YAML] [--seed S] [--out DIR] [--threads N]\n"
    "                  [--target-spacing M] [--candidate-spacing M] [--max-candidates N] [--path-iterations N]\n"
    "                  [--cover-fraction F] [--online-path M] [--online-min MIN] [--up-axis z|y] [--scale S]\n"
    "                  [--fit-size X,Y,Z] [--offset X,Y,Z] [--crop-min X,Y,Z] [--crop-max X,Y,Z]\n"
    "  --config defaults to config/<scene name>.yaml of the package when it exists.\n";

int fail(const std::string& message) {
  std::cerr << "nbv_oracle: " << message << "\n";
  return 2;
}

Status writePath(const std::string& file, const OracleResult& r) {
  std::ofstream out(file);
  out << "index,x_m,y_m,z_m,yaw_rad,s_m,viewpoint\n";
  double s = 0.0;
  for (size_t i = 0; i < r.path.size(); ++i) {
    if (i > 0) s += (r.path[i].head<3>() - r.path[i - 1].head<3>()).norm();
    const Eigen::Vector4d& q = r.path[i];
    out << i << "," << q.x() << "," << q.y() << "," << q.z() << "," << q.w() << "," << s << ","
        << r.path_viewpoint[i] << "\n";
  }
  return out ? Status::Ok() : Status::Error("cannot write " + file);
}

// The oracle's timed path sampled every 1 / frame_rate s from 0, and once at
// its end (the last viewpoint), as nbv_mission's path.csv.
Status writeFlight(const std::string& file, const Trajectory& timed, double frame_rate) {
  std::vector<double> t;
  std::vector<Eigen::Vector4d> poses;
  for (size_t i = 0; !timed.empty(); ++i) {
    t.push_back(std::min(timed.endTime(), i / frame_rate));
    const TrajectorySample q = timed.sample(t.back());
    poses.emplace_back(q.p_W.x(), q.p_W.y(), q.p_W.z(), q.yaw);
    if (t.back() >= timed.endTime() - 1e-9) break;
  }
  return writeFlightCsv(file, t, poses);
}

Status writePoints(const std::string& file, const std::vector<Eigen::Vector3d>& points) {
  std::ofstream out(file);
  out << "x_m,y_m,z_m\n";
  for (const Eigen::Vector3d& p : points) out << p.x() << "," << p.y() << "," << p.z() << "\n";
  return out ? Status::Ok() : Status::Error("cannot write " + file);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> options = sceneOptionNames();
  options.insert(options.end(), {"config", "seed", "out", "threads", "target-spacing", "candidate-spacing",
                                 "max-candidates", "path-iterations", "cover-fraction", "online-path",
                                 "online-min"});
  CliArgs args(options, {"help"});
  bool help = false;
  if (Status s = args.parseCommand(argc, argv, kUsage, std::cout, &help); !s) return fail(s.message());
  if (help) return 0;
  MissionConfig mission;
  std::string config_file;
  if (Status s = missionConfigFromArgs(args, NBV_SOURCE_DIR, &mission, &config_file); !s) return fail(s.message());
  int seed = 1, max_candidates = 0;
  double online_path = 0.0, online_min = 0.0;
  if (Status s = mission.validate(); !s) return fail((config_file.empty() ? "" : config_file + ": ") + s.message());
  OracleConfig config = oracleConfigFrom(mission);
  max_candidates = static_cast<int>(config.max_candidates);
  const Status parsed[] = {args.getInt("seed", &seed), args.getInt("threads", &config.threads),
                           args.getDouble("target-spacing", &config.target_spacing),
                           args.getDouble("candidate-spacing", &config.candidate_spacing),
                           args.getInt("max-candidates", &max_candidates),
                           args.getInt("path-iterations", &config.path_iterations),
                           args.getDouble("cover-fraction", &config.cover_fraction),
                           args.getDouble("online-path", &online_path), args.getDouble("online-min", &online_min)};
  for (const Status& s : parsed)
    if (!s) return fail(s.message());
  if (seed < 0 || max_candidates < 1) return fail("--seed expects >= 0 and --max-candidates >= 1");
  config.seed = static_cast<unsigned>(seed);
  config.max_candidates = static_cast<size_t>(max_candidates);
  if (Status s = config.validate(); !s) return fail(s.message());

  const std::string scene_name = std::filesystem::path(mission.scene.scene).stem().string();
  const std::string out_dir = args.get("out", "output/oracle_" + scene_name);
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) return fail("cannot create '" + out_dir + "': " + ec.message());
  TriangleMesh mesh;
  if (Status s = loadScene(mission.scene, &mesh); !s) return fail(s.message());
  std::unique_ptr<RaycastScene> scene;
  if (Status s = RaycastScene::create(mesh, &scene); !s) return fail(s.message());
  std::printf("scene '%s': %zu triangles, %.0f m^2; config %s; voxel %.2f m, delta_pose %.2f m; seed %d\n",
              mission.scene.scene.c_str(), mesh.numTriangles(), mesh.area(),
              config_file.empty() ? "(defaults)" : config_file.c_str(), config.tsdf.voxel_size, config.delta_pose,
              seed);
  std::fflush(stdout);

  OraclePlanner oracle(config, mesh, *scene);
  oracle.setProgress([](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  });
  const OracleResult r = oracle.plan();
  if (!r.status) return fail(r.status.message());
  if (Status s = writePath(out_dir + "/oracle_path.csv", r); !s) return fail(s.message());
  if (Status s = writePoints(out_dir + "/oracle_uncoverable.csv", r.uncoverable); !s) return fail(s.message());
  if (Status s = writeFlight(out_dir + "/oracle_flight.csv", r.timed, mission.frame_rate); !s) return fail(s.message());

  const double flight_min = r.flight_time / 60.0, wall_s = r.times.total / 1000.0;
  const double path_ratio = online_path > 0.0 ? online_path / r.path_length : NAN;
  const double time_ratio = online_min > 0.0 ? online_min / flight_min : NAN;
  JsonWriter json;
  json.beginObject().value("scene", mission.scene.scene).value("config", config_file).value("seed", seed);
  json.value("voxel_size_m", config.tsdf.voxel_size).value("delta_pose_m", config.delta_pose);
  json.value("collision_radius_m", config.path.collision_radius).value("target_spacing_m", config.target_spacing);
  json.value("cover_fraction_goal", config.cover_fraction);
  json.value("candidate_spacing_m", config.candidate_spacing).value("targets", r.targets);
  json.value("coverable", r.coverable).value("uncoverable", r.uncoverable.size()).value("covered", r.covered);
  json.value("covered_fraction", r.coveredFraction()).value("candidates_built", r.candidates_built);
  json.value("candidates", r.candidates).value("viewpoints", r.viewpoints.size());
  json.value("tour_status", toString(r.tour_status)).value("straight_tour_m", r.tour_length);
  json.value("failed_legs", r.failed_legs).value("path_length_m", r.path_length);
  json.value("flight_time_s", r.flight_time).value("flight_min", flight_min).value("wall_s", wall_s);
  json.value("online_path_ratio", path_ratio).value("online_time_ratio", time_ratio);
  json.beginObject("step_ms").value("targets", r.times.targets).value("map", r.times.map);
  json.value("candidates", r.times.candidates).value("visibility", r.times.visibility).value("cover", r.times.cover);
  json.value("tour", r.times.tour).value("paths", r.times.paths).endObject();
  json.beginArray("tour");
  for (int k : r.order) {
    const Eigen::Vector4d& q = r.viewpoints[k];
    json.beginObject().value("viewpoint", k).value("x", q.x()).value("y", q.y()).value("z", q.z());
    json.value("yaw", q.w()).value("gain", r.gains[k]).endObject();
  }
  json.endArray().endObject();
  std::ofstream(out_dir + "/oracle.json") << json.str();

  char line[512];
  std::ofstream md(out_dir + "/oracle.md");
  md << "# Oracle reference on `" << mission.scene.scene << "` (seed " << seed << ")\n\nConfig: `" << config_file
     << "`, voxel " << config.tsdf.voxel_size << " m, delta_pose " << config.delta_pose << " m, radius "
     << config.path.collision_radius << " m, targets every " << config.target_spacing << " m, cover goal "
     << 100.0 * config.cover_fraction << " %.\n\n"
     << "| targets | coverable | chosen viewpoints | covered [%] | straight tour [m] | path [m] | flight [min] | "
        "failed legs | wall [s] |\n|---|---|---|---|---|---|---|---|---|\n";
  std::snprintf(line, sizeof(line), "| %zu | %zu | %zu | %.2f | %.1f | %.1f | %.1f | %zu | %.1f |\n", r.targets,
                r.coverable, r.viewpoints.size(), 100.0 * r.coveredFraction(), r.tour_length, r.path_length,
                flight_min, r.failed_legs, wall_s);
  md << line << "\n" << r.uncoverable.size() << " targets are seen by no candidate viewpoint and are excluded; "
     << r.candidates << " candidates of " << r.candidates_built << " built are collision-free and reachable.\n";
  if (online_path > 0.0 || online_min > 0.0) {
    std::snprintf(line, sizeof(line), "\nOnline / oracle: path %.2f, flight time %.2f.\n", path_ratio, time_ratio);
    md << line;
  }
  std::printf("summary: %zu coverable targets (%zu excluded), %zu viewpoints cover %.2f %%, path %.1f m "
              "(straight tour %.1f m), flight %.1f min, %zu failed legs, wall %.1f s\n",
              r.coverable, r.uncoverable.size(), r.viewpoints.size(), 100.0 * r.coveredFraction(), r.path_length,
              r.tour_length, flight_min, r.failed_legs, wall_s);
  if (online_path > 0.0 || online_min > 0.0)
    std::printf("online / oracle: path %.2f, flight time %.2f\n", path_ratio, time_ratio);
  std::printf("wrote %s/oracle.json, oracle.md, oracle_path.csv, oracle_flight.csv, oracle_uncoverable.csv\n",
              out_dir.c_str());
  return r.failed_legs == 0 ? 0 : 1;
}
