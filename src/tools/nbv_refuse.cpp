// nbv_refuse: re-fuses a recorded flight into a fresh TSDF with the
// parameters of a mission YAML (optionally overridden), meshes it and
// evaluates the mesh against the scene's ground truth, so that fusion and
// meshing parameters can be compared on exactly the same flight (a flown
// mission changes chaotically with any change of the map).
//
//   nbv_refuse --path PATH.csv [--scene plant|statue|FILE] [--config YAML] [--truncation M]
//              [--mesh-truncation M] [--mesh-voxel-size V] [--mesh-weight-dropoff 0|1] [--mesh-min-weight W]
//              [--seed S] [--threads N] [--out DIR] [--observed]
//
// PATH.csv is nbv_mission's trial_K/path.csv: header t_s,x_m,y_m,z_m,yaw_rad,
// one base_link pose per integrated depth frame. Every frame is fused as
// MissionRunner::run() fuses it (same weight scale, same mesh layer, same
// take-off free ball, same camera noise seed for --seed S), so with the
// trial's config and seed the result is that trial's reconstruction.
// Writes DIR/reconstruction.ply, DIR/eval/ (nbv_evaluate's report) and
// DIR/refuse.json (inputs, effective parameters and results). Exit code 2 on
// any bad input. --observed also measures what the camera saw, whatever the
// fusion: the share of the visible ground truth within e_max of a measured
// depth point (every 4th pixel of every frame, kept once per 5 cm cell), the
// bound any fusion of this flight could reach.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <unordered_set>

#include "surface_nbv/eval/evaluator.h"
#include "surface_nbv/eval/report_writer.h"
#include "surface_nbv/map/mesh_extractor.h"
#include "surface_nbv/map/mesh_layer.h"
#include "surface_nbv/map/tsdf_integrator.h"
#include "surface_nbv/mission/flight_csv.h"
#include "surface_nbv/mission/mission_config.h"
#include "surface_nbv/mission/scene_defaults.h"
#include "surface_nbv/sensor/camera_mount.h"
#include "surface_nbv/sensor/depth_points.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/util/cli_args.h"
#include "surface_nbv/util/json_writer.h"

using namespace surface_nbv;

namespace {

using Clock = std::chrono::steady_clock;

const char* kUsage =
    "usage: nbv_refuse --path PATH.csv [--scene plant|statue|FILE] [--config YAML] [--truncation M]\n"
    "                  [--mesh-truncation M] [--mesh-voxel-size V] [--mesh-weight-dropoff 0|1] [--mesh-min-weight W]\n"
    "                  [--seed S] [--threads N] [--out DIR]\n"
    "                  [--up-axis z|y] [--scale S] [--fit-size X,Y,Z] [--offset X,Y,Z] [--crop-min X,Y,Z]\n"
    "                  [--crop-max X,Y,Z] [--observed]\n"
    "  Re-fuses the poses of PATH.csv (nbv_mission's trial_K/path.csv) with the config's TSDF parameters,\n"
    "  meshes and evaluates the result. --config defaults to config/<scene name>.yaml of the package when it\n"
    "  exists; --seed is the mission seed of the trial (camera noise seed = camera.noise_seed + S, default 1);\n"
    "  --out defaults to output/refuse_<scene name>. --observed also reports the coverage of the measured depth\n"
    "  points themselves (what the camera saw, whatever the fusion).\n";

int fail(const std::string& message) {
  std::cerr << "nbv_refuse: " << message << "\n";
  return 2;
}

// One row of path.csv: a base_link pose in the world frame.
struct PathRow {
  size_t line = 0;  // 1-based line number in the file
  double t = 0.0;
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  double yaw = 0.0;
};

std::string trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const size_t e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// Reads nbv_mission's path.csv. Error naming the file and line on a missing
// or unreadable file, a wrong header, a row without exactly five finite
// numbers, or no row at all. Blank lines at the end of the file are ignored.
Status readPath(const std::string& file, std::vector<PathRow>* rows) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return Status::Error("path file '" + file + "' does not exist");
  if (!std::filesystem::is_regular_file(file, ec)) {
    return Status::Error("path file '" + file + "' is not a regular file");
  }
  std::ifstream in(file);
  if (!in) return Status::Error("cannot open path file '" + file + "'");
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(trim(line));
  if (in.bad()) return Status::Error("cannot read path file '" + file + "'");
  while (!lines.empty() && lines.back().empty()) lines.pop_back();
  const std::string header = kFlightCsvHeader;
  if (lines.empty()) return Status::Error(file + ": empty file, expected the header '" + header + "' and poses");
  if (lines[0] != header) {
    return Status::Error(file + ":1: expected the header '" + header + "', got '" + lines[0] + "'");
  }
  static const char* const kColumns[] = {"t_s", "x_m", "y_m", "z_m", "yaw_rad"};
  rows->clear();
  for (size_t i = 1; i < lines.size(); ++i) {
    const std::string where = file + ":" + std::to_string(i + 1) + ": ";
    std::vector<std::string> fields;
    std::stringstream ss(lines[i]);
    for (std::string field; std::getline(ss, field, ',');) fields.push_back(trim(field));
    if (!lines[i].empty() && lines[i].back() == ',') fields.push_back("");
    if (fields.size() != 5) {
      return Status::Error(where + "expected 5 comma-separated numbers (" + kFlightCsvHeader + "), got " +
                           std::to_string(fields.size()) + " field(s)");
    }
    double v[5];
    for (int k = 0; k < 5; ++k) {
      const std::string& text = fields[k];
      char* end = nullptr;
      v[k] = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size()) {
        return Status::Error(where + kColumns[k] + " '" + text + "' is not a number");
      }
      if (!std::isfinite(v[k])) return Status::Error(where + kColumns[k] + " '" + text + "' is not finite");
    }
    PathRow row;
    row.line = i + 1;
    row.t = v[0];
    row.p_W = Eigen::Vector3d(v[1], v[2], v[3]);
    row.yaw = v[4];
    rows->push_back(row);
  }
  if (rows->empty()) return Status::Error(file + ": no poses after the header");
  return Status::Ok();
}

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The measured depth points of a flight, kept once per cubic cell.
class ObservedCells {
 public:
  static constexpr double kCell = 0.05;  // [m]
  static constexpr int kPixelStep = 4;

  void add(const DepthCamera& camera, const DepthImage& depth, const Transform& T_W_C) {
    depthToPoints(camera, depth, &points_C_, kPixelStep);
    for (const Eigen::Vector3f& p_C : points_C_) {
      if (camera.depthInRange(p_C.z())) cells_.insert(key(T_W_C * p_C.cast<double>()));
    }
  }
  size_t size() const { return cells_.size(); }
  // Cell centres.
  std::vector<Eigen::Vector3f> points() const {
    std::vector<Eigen::Vector3f> out;
    out.reserve(cells_.size());
    for (uint64_t k : cells_) {
      const auto axis = [&](int shift) {
        return static_cast<float>(((static_cast<int64_t>((k >> shift) & 0x1fffff)) - kBias + 0.5) * kCell);
      };
      out.emplace_back(axis(0), axis(21), axis(42));
    }
    return out;
  }

 private:
  static constexpr int64_t kBias = 1 << 20;  // 21 bits per axis: +-52 km at 5 cm
  static uint64_t key(const Eigen::Vector3d& p) {
    uint64_t k = 0;
    for (int a = 0; a < 3; ++a) {
      const int64_t i = static_cast<int64_t>(std::floor(p[a] / kCell)) + kBias;
      k |= static_cast<uint64_t>(std::clamp<int64_t>(i, 0, 0x1fffff)) << (21 * a);
    }
    return k;
  }
  std::unordered_set<uint64_t> cells_;
  std::vector<Eigen::Vector3f> points_C_;  // one frame's points, kept between frames
};

}  // namespace

int main(int argc, char** argv) {
  const auto wall0 = Clock::now();
  std::vector<std::string> options = sceneOptionNames();
  options.insert(options.end(),
                 {"path", "config", "truncation", "mesh-truncation", "mesh-voxel-size", "mesh-weight-dropoff", "mesh-min-weight",
                  "seed", "threads", "out"});
  CliArgs args(options, {"help", "observed"});
  bool help = false;
  if (Status s = args.parseCommand(argc, argv, kUsage, std::cout, &help); !s) return fail(s.message());
  if (help) return 0;
  if (!args.has("path")) return fail("--path PATH.csv is required (nbv_mission's trial_K/path.csv)");
  const std::string path_file = args.get("path", "");

  MissionConfig config;
  std::string config_file;
  if (Status s = missionConfigFromArgs(args, NBV_SOURCE_DIR, &config, &config_file); !s) return fail(s.message());
  int seed = 1, dropoff = config.tsdf.mesh_weight_dropoff ? 1 : 0;
  double mesh_min_weight = config.tsdf.mesh_min_weight;
  const Status parsed[] = {args.getDouble("truncation", &config.tsdf.truncation),
                           args.getDouble("mesh-truncation", &config.tsdf.mesh_truncation),
                           args.getDouble("mesh-voxel-size", &config.tsdf.mesh_voxel_size),
                           args.getInt("mesh-weight-dropoff", &dropoff),
                           args.getDouble("mesh-min-weight", &mesh_min_weight), args.getInt("seed", &seed),
                           args.getInt("threads", &config.threads)};
  for (const Status& s : parsed)
    if (!s) return fail(s.message());
  if (seed < 0) return fail("--seed expects an integer >= 0");
  if (dropoff != 0 && dropoff != 1) return fail("--mesh-weight-dropoff expects 0 or 1");
  config.tsdf.mesh_weight_dropoff = dropoff == 1;
  if (!(std::abs(mesh_min_weight) <= std::numeric_limits<float>::max())) {
    return fail("--mesh-min-weight expects a finite number (< 0 selects w_th)");
  }
  config.tsdf.mesh_min_weight = static_cast<float>(mesh_min_weight);
  config.seed = static_cast<unsigned>(seed);
  if (Status s = config.validate(); !s) {
    const bool overridden = args.has("truncation") || args.has("mesh-truncation") || args.has("mesh-voxel-size") ||
                            args.has("mesh-weight-dropoff") || args.has("mesh-min-weight") || args.has("threads");
    const std::string source = config_file.empty() ? "default config" : config_file;
    return fail(source + (overridden ? " with the command-line overrides" : "") + ": " + s.message());
  }

  std::vector<PathRow> rows;
  if (Status s = readPath(path_file, &rows); !s) return fail(s.message());
  TriangleMesh mesh;
  if (Status s = loadScene(config.scene, &mesh); !s) return fail(s.message());
  std::unique_ptr<RaycastScene> scene;
  if (Status s = RaycastScene::create(mesh, &scene); !s) return fail(s.message());
  const std::string scene_name = std::filesystem::path(config.scene.scene).stem().string();
  const std::string out_dir = args.get("out", "output/refuse_" + scene_name);
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) return fail("cannot create '" + out_dir + "': " + ec.message());

  // Fusion as MissionRunner::run(): planning map, mesh layer, weight scale,
  // take-off free ball, camera noise seed, frame index as render seed.
  TsdfConfig tsdf = config.tsdf;
  tsdf.threads = config.threads;
  TsdfMap map(tsdf);
  TsdfIntegrator integrator(&map);
  integrator.setWeightScale(std::max(1.0, config.camera.rate_hz / config.frame_rate));
  MeshLayer mesh_layer(&map);
  mesh_layer.setWeightScale(integrator.weightScale());
  CameraConfig camera_config = config.camera;
  camera_config.noise_seed = config.camera.noise_seed + config.seed;
  const DepthCamera camera(camera_config);
  const DepthRenderer renderer(*scene, camera, config.threads);
  const Transform T_B_C = opticalInBody(camera_config);
  const TsdfConfig& meshed = mesh_layer.map().config();
  std::printf("scene '%s': %zu triangles; config %s; voxel %.2f m, truncation %.3f m, mesh voxel %.3f m, "
              "mesh truncation %.3f m%s%s, "
              "mesh_min_weight %g; %zu frames from %s (seed %d)\n",
              config.scene.scene.c_str(), mesh.numTriangles(), config_file.empty() ? "(defaults)" : config_file.c_str(),
              tsdf.voxel_size, tsdf.truncationDistance(), meshed.voxel_size, meshed.truncationDistance(),
              mesh_layer.separate() ? " (separate layer)" : " (the map itself)",
              meshed.weight_dropoff ? ", weight drop-off" : "", meshed.mesh_min_weight, rows.size(),
              path_file.c_str(), seed);
  std::fflush(stdout);

  if (config.start_free_radius > 0.0) {
    Status s = integrator.markFree(config.start.head<3>(), config.start_free_radius);
    if (s) s = mesh_layer.markFree(config.start.head<3>(), config.start_free_radius);
    if (!s) return fail("take-off free ball: " + s.message());
  }
  const auto fuse0 = Clock::now();
  DepthImage depth;
  const bool observe = args.has("observed");
  ObservedCells observed;
  int reported_tenths = 0;
  for (size_t i = 0; i < rows.size(); ++i) {
    const PathRow& row = rows[i];
    const Transform T_W_C = levelBodyPose(row.p_W, row.yaw) * T_B_C;
    renderer.render(T_W_C, &depth, i);
    if (observe) observed.add(camera, depth, T_W_C);
    const Status fused = mesh_layer.integrateDepthWith(&integrator, camera, depth, T_W_C, config.threads);
    if (!fused) {
      return fail(path_file + ":" + std::to_string(row.line) + ": integration of frame " + std::to_string(i) +
                  " (t = " + std::to_string(row.t) + " s) failed: " + fused.message());
    }
    const int tenths = static_cast<int>(10 * (i + 1) / rows.size());
    if (tenths > reported_tenths) {
      reported_tenths = tenths;
      std::printf("  fused %zu / %zu frames (%d %%), %.1f s\n", i + 1, rows.size(), 10 * tenths,
                  secondsSince(fuse0));
      std::fflush(stdout);
    }
  }
  const double fuse_s = secondsSince(fuse0);

  MeshExtractor mesher;
  mesher.update(mesh_layer.map());
  const TriangleMesh reconstruction = mesher.mesh();
  const std::string ply = out_dir + "/reconstruction.ply";
  if (reconstruction.empty()) {
    std::filesystem::remove(ply, ec);  // no stale mesh of an earlier run
    std::printf("  the reconstruction is empty: no %s written\n", ply.c_str());
  } else if (Status s = saveMesh(reconstruction, ply); !s) {
    return fail(s.message());
  }
  const EvalConfig eval_config = missionEvalConfig(config);
  EvalResult eval;
  if (Status s = Evaluator(eval_config).evaluate(mesh, reconstruction, &eval); !s) return fail(s.message());
  if (Status s = ReportWriter(eval, {ply, config.scene.scene}).write(out_dir + "/eval"); !s) return fail(s.message());
  double observed_coverage = -1.0, seen_not_meshed = 0.0, meshed_not_seen = 0.0;  // shares of the visible samples
  if (observe) {
    const std::vector<Eigen::Vector3f> points = observed.points();
    const PointIndex index(points);
    const CoverageResult seen =
        computeCoverage(eval.ground_truth, eval.visible, index, eval_config.eMax(), config.threads);
    observed_coverage = seen.coverage();
    // Seen but not in the mesh (what fusion and meshing lose), and the reverse.
    const double share = 1.0 / std::max<size_t>(1, eval.numVisible());
    for (size_t i = 0; i < eval.ground_truth.size(); ++i) {
      if (!eval.visible[i]) continue;
      if (seen.covered[i] && !eval.coverage.covered[i]) seen_not_meshed += share;
      if (!seen.covered[i] && eval.coverage.covered[i]) meshed_not_seen += share;
    }
    std::printf("observed: %zu cells of %.0f cm hold %.2f %% of the visible ground truth within e_max; "
                "%.2f %% seen but not covered by the mesh, %.2f %% covered but not seen\n",
                points.size(), 100.0 * ObservedCells::kCell, 100.0 * observed_coverage,
                100.0 * seen_not_meshed, 100.0 * meshed_not_seen);
  }
  const double wall_s = secondsSince(wall0);

  JsonWriter json;
  json.beginObject().value("path", path_file).value("scene", config.scene.scene).value("config", config_file);
  json.value("seed", seed).value("threads", config.threads).value("voxel_size_m", tsdf.voxel_size);
  json.value("truncation_m", tsdf.truncationDistance()).value("mesh_layer", mesh_layer.separate());
  json.value("mesh_voxel_size_m", meshed.voxel_size).value("mesh_truncation_m", meshed.truncationDistance()).value("mesh_weight_dropoff", meshed.weight_dropoff);
  json.value("mesh_min_weight", static_cast<double>(meshed.mesh_min_weight));
  json.value("w_th", static_cast<double>(tsdf.w_th)).value("weight_scale", integrator.weightScale());
  json.value("frames", rows.size()).value("triangles", reconstruction.numTriangles());
  json.value("e_max_m", eval_config.eMax()).value("coverage", eval.coverage.coverage());
  json.value("error_mean_m", eval.error_stats.mean).value("error_std_m", eval.error_stats.std_dev);
  if (observe) {
    json.value("observed_coverage", observed_coverage).value("observed_cells", observed.size());
    json.value("seen_not_meshed", seen_not_meshed).value("meshed_not_seen", meshed_not_seen);
  }
  json.value("rmse_m", eval.error_stats.rmse).value("fuse_s", fuse_s).value("wall_s", wall_s).endObject();
  std::ofstream out(out_dir + "/refuse.json");
  out << json.str();
  if (!out) return fail("cannot write " + out_dir + "/refuse.json");

  std::printf("refused %zu frames: coverage %.2f %%, error mean %.2f cm, std %.2f cm, RMSE %.2f cm -> %s\n",
              rows.size(), 100.0 * eval.coverage.coverage(), 100.0 * eval.error_stats.mean,
              100.0 * eval.error_stats.std_dev, 100.0 * eval.error_stats.rmse, out_dir.c_str());
  return 0;
}
