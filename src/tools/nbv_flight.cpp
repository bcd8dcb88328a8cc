// nbv_flight: renders depth along a scripted flight around a scene (no ROS
// master needed), fuses every frame into the TSDF map and reports what the
// camera saw and what the map holds: frames, valid pixels, render and
// integration times, known voxels, the reconstructed mesh, depth pictures.
// The main job until the planner flies.
//
//   nbv_flight [--scene plant] [--standoff 5] [--levels 2] [--step 0.25]
//              [--voxel 0.3] [--threads 2] [--noise-k 0] [--seed 1]
//              [--out DIR] [--pictures 6]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "surface_nbv/eval/evaluator.h"
#include "surface_nbv/map/map_io.h"
#include "surface_nbv/map/mesh_extractor.h"
#include "surface_nbv/map/tsdf_integrator.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/sim/scene_source.h"
#include "surface_nbv/sim/scripted_flight.h"
#include "surface_nbv/util/json_writer.h"
#include "surface_nbv/util/png_writer.h"

using namespace surface_nbv;

namespace {

struct FrameRecord {
  double s, ms, integrate_ms, valid_fraction, min_z, max_z;
};

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(std::min<double>(v.size() - 1, p * (v.size() - 1) + 0.5))];
}

int fail(const std::string& message) {
  std::cerr << "nbv_flight: " << message << "\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> options = sceneOptionNames();
  options.insert(options.end(), {"standoff", "levels", "step", "voxel", "threads", "noise-k", "seed", "out", "pictures"});
  CliArgs args(options, {"help"});
  if (Status s = args.parse(argc, argv); !s) return fail(s.message());
  if (args.has("help")) {
    std::cout << "usage: nbv_flight [--scene NAME|FILE] [--up-axis z|y] [--scale S] [--fit-size X,Y,Z]\n"
                 "                  [--offset X,Y,Z] [--crop-min X,Y,Z] [--crop-max X,Y,Z] [--standoff M] [--levels N] [--step M] [--voxel M]\n"
                 "                  [--threads N]\n"
                 "                  [--noise-k K] [--seed N] [--out DIR] [--pictures N]\n";
    return 0;
  }
  SceneConfig scene_config;
  double standoff = 5.0, step = 0.25, voxel = 0.3;
  int levels = 2, threads = 2, pictures = 6, seed = 1;
  CameraConfig camera_config;
  const Status parsed[] = {sceneConfigFromArgs(args, &scene_config), args.getDouble("standoff", &standoff),
                           args.getDouble("step", &step),           args.getInt("levels", &levels),
                           args.getDouble("voxel", &voxel),
                           args.getInt("threads", &threads),        args.getInt("pictures", &pictures),
                           args.getInt("seed", &seed),              args.getDouble("noise-k", &camera_config.noise_k)};
  for (const Status& s : parsed) {
    if (!s) return fail(s.message());
  }
  camera_config.noise_seed = static_cast<uint64_t>(seed);
  if (Status s = camera_config.validate(); !s) return fail(s.message());
  if (!(step > 0.0) || levels < 1 || threads < 1) return fail("--step expects > 0, --levels and --threads >= 1");
  const std::string out_dir = args.get("out", "output/flight_" + std::filesystem::path(scene_config.scene).stem().string());
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) return fail("cannot create output directory '" + out_dir + "': " + ec.message());

  TriangleMesh mesh;
  if (Status s = loadScene(scene_config, &mesh); !s) return fail(s.message());
  std::unique_ptr<RaycastScene> scene;
  if (Status s = RaycastScene::create(mesh, &scene); !s) return fail(s.message());
  const AlignedBox bounds = mesh.bounds();
  FlightConfig flight_config = flightAround(bounds, standoff, levels, 0.5);
  if (Status s = flight_config.validate(); !s) return fail(s.message());
  const ScriptedFlight flight(flight_config);
  const DepthCamera camera(camera_config);
  const DepthRenderer renderer(*scene, camera, threads);
  const Transform T_B_C = opticalInBody(camera_config);
  TsdfConfig tsdf_config;
  tsdf_config.voxel_size = voxel;
  tsdf_config.threads = threads;
  const Eigen::Vector3d margin(standoff + 2.0, standoff + 2.0, 2.0);
  tsdf_config.bounds = AlignedBox(bounds.min - margin, bounds.max + margin);
  tsdf_config.bounds.min.z() = std::min(bounds.min.z(), 0.0) - 0.5;
  if (Status s = tsdf_config.validate(); !s) return fail(s.message());
  TsdfMap map(tsdf_config);
  TsdfIntegrator integrator(&map);

  std::printf("scene '%s': %zu triangles, bounds [%.1f %.1f %.1f] - [%.1f %.1f %.1f] m\n", scene_config.scene.c_str(),
              mesh.numTriangles(), bounds.min.x(), bounds.min.y(), bounds.min.z(), bounds.max.x(), bounds.max.y(),
              bounds.max.z());
  const int frames = static_cast<int>(flight.length() / step) + 1;
  std::printf("flight: %.1f m in %d loop(s), %d frames every %.2f m, %d render thread(s)\n", flight.length(), levels,
              frames, step, threads);

  std::vector<FrameRecord> records;
  std::vector<double> times, integrate_times;
  DepthImage depth;
  const int picture_every = pictures > 0 ? std::max(1, frames / pictures) : frames + 1;
  int next_progress = 0;
  for (int i = 0; i < frames; ++i) {
    const double s = std::min(flight.length(), i * step);
    const Transform T_W_C = flight.poseAtDistance(s) * T_B_C;
    const auto t0 = std::chrono::steady_clock::now();
    renderer.render(T_W_C, &depth, static_cast<uint64_t>(i));
    const double ms = msSince(t0);
    const auto t1 = std::chrono::steady_clock::now();
    if (Status st = integrator.integrateDepth(camera, depth, T_W_C); !st) return fail(st.message());
    const double integrate_ms = msSince(t1);
    double lo = 1e9, hi = 0.0;
    for (float z : depth.data) {
      if (std::isfinite(z)) lo = std::min<double>(lo, z), hi = std::max<double>(hi, z);
    }
    const double valid = static_cast<double>(depth.validCount()) / depth.data.size();
    records.push_back({s, ms, integrate_ms, valid, valid > 0 ? lo : NAN, valid > 0 ? hi : NAN});
    times.push_back(ms);
    integrate_times.push_back(integrate_ms);
    if (i % picture_every == 0) {
      char name[64];
      std::snprintf(name, sizeof(name), "/depth_%04d.png", i);
      const auto rgb = colorizeDepth(depth.data, static_cast<float>(camera_config.min_range),
                                     static_cast<float>(camera_config.max_range));
      if (Status st = writePng(out_dir + name, depth.width, depth.height, 3, rgb); !st) return fail(st.message());
    }
    if (100 * (i + 1) / frames >= next_progress) {
      std::printf("  %3d%%  frame %d/%d  s = %.1f m  valid %.1f%%  %.2f ms\n", 100 * (i + 1) / frames, i + 1, frames, s,
                  100.0 * valid, ms);
      std::fflush(stdout);
      next_progress += 10;
    }
  }

  size_t seeing = 0;
  double valid_sum = 0.0;
  for (const FrameRecord& r : records) {
    seeing += r.valid_fraction > 0.01 ? 1 : 0;
    valid_sum += r.valid_fraction;
  }
  const double median_ms = percentile(times, 0.5), p95_ms = percentile(times, 0.95);
  const double integrate_median_ms = percentile(integrate_times, 0.5);
  if (Status s = saveMesh(mesh, out_dir + "/scene.ply"); !s) return fail(s.message());
  size_t known = 0, occupied = 0;
  for (const auto& b : map.blocks()) {
    for (const TsdfVoxel& v : b->voxels) {
      known += v.w >= tsdf_config.w_th ? 1 : 0;
      occupied += v.w >= tsdf_config.w_th && v.phi <= 0.0f ? 1 : 0;
    }
  }
  MeshExtractor mesher;
  mesher.update(map);
  const TriangleMesh reconstruction = mesher.mesh();
  if (Status s = saveMesh(reconstruction, out_dir + "/reconstruction.ply"); !s) return fail(s.message());
  if (Status s = saveMap(map, out_dir + "/map.tsdf"); !s) return fail(s.message());
  EvalConfig eval_config;
  eval_config.voxel_size = voxel;
  eval_config.threads = threads;
  EvalResult eval;
  if (Status s = Evaluator(eval_config).evaluate(mesh, reconstruction, &eval); !s) return fail(s.message());

  JsonWriter json;
  json.beginObject()
      .value("scene", scene_config.scene)
      .value("triangles", mesh.numTriangles())
      .value("path_length_m", flight.length())
      .value("flight_time_s", flight.duration())
      .value("frames", records.size())
      .value("frames_seeing_structure", seeing)
      .value("mean_valid_fraction", valid_sum / records.size())
      .value("render_threads", threads)
      .value("render_median_ms", median_ms)
      .value("render_p95_ms", p95_ms)
      .value("rays_per_second", camera_config.width * camera_config.height / (median_ms * 1e-3))
      .value("voxel_size_m", voxel)
      .value("integrate_median_ms", integrate_median_ms)
      .value("map_blocks", map.numBlocks())
      .value("map_bytes", map.memoryBytes())
      .value("known_voxels", known)
      .value("occupied_voxels", occupied)
      .value("reconstruction_triangles", reconstruction.numTriangles())
      .value("reconstruction_area_m2", reconstruction.area())
      .value("scene_area_m2", mesh.area())
      .value("coverage", eval.coverage.coverage())
      .value("error_mean_m", eval.error_stats.mean)
      .value("error_std_m", eval.error_stats.std_dev)
      .value("rmse_m", eval.error_stats.rmse);
  json.beginArray("per_frame");
  for (const FrameRecord& r : records) {
    json.beginObject().value("s_m", r.s).value("ms", r.ms).value("integrate_ms", r.integrate_ms);
    json.value("valid_fraction", r.valid_fraction);
    json.value("min_depth_m", r.min_z).value("max_depth_m", r.max_z).endObject();
  }
  json.endArray().endObject();
  std::ofstream(out_dir + "/report.json") << json.str();

  std::ofstream md(out_dir + "/report.md");
  md << "# Scripted flight around `" << scene_config.scene << "`\n\n"
     << "| figure | value |\n|---|---|\n"
     << "| triangles | " << mesh.numTriangles() << " |\n"
     << "| path length | " << flight.length() << " m |\n"
     << "| flight time at 0.5 m/s | " << flight.duration() << " s |\n"
     << "| frames | " << records.size() << " |\n"
     << "| frames seeing the structure | " << seeing << " |\n"
     << "| mean valid pixels | " << 100.0 * valid_sum / records.size() << " % |\n"
     << "| render time, median / p95 (" << threads << " threads) | " << median_ms << " / " << p95_ms << " ms |\n"
     << "| TSDF integration, median (" << voxel << " m voxels) | " << integrate_median_ms << " ms |\n"
     << "| map blocks / known voxels / occupied voxels | " << map.numBlocks() << " / " << known << " / " << occupied
     << " |\n"
     << "| reconstruction | " << reconstruction.numTriangles() << " triangles, " << reconstruction.area()
     << " m^2 (scene: " << mesh.area() << " m^2) |\n"
     << "| coverage of the visible ground truth (e_max = " << 100.0 * voxel * std::sqrt(3.0) / 2.0 << " cm) | "
     << 100.0 * eval.coverage.coverage() << " % |\n"
     << "| signed error mean / std / RMSE | " << 100.0 * eval.error_stats.mean << " / "
     << 100.0 * eval.error_stats.std_dev << " / " << 100.0 * eval.error_stats.rmse << " cm |\n";

  std::printf("frames: %zu, seeing the structure: %zu, mean valid pixels: %.1f%%\n", records.size(), seeing,
              100.0 * valid_sum / records.size());
  std::printf("render time: median %.2f ms, p95 %.2f ms (%d threads, %dx%d)\n", median_ms, p95_ms, threads,
              camera_config.width, camera_config.height);
  std::printf("TSDF at %.2f m: integration median %.2f ms, %zu blocks, %zu known voxels, mesh of %zu triangles "
              "(%.0f m^2 of %.0f m^2 scene surface)\n",
              voxel, integrate_median_ms, map.numBlocks(), known, reconstruction.numTriangles(), reconstruction.area(),
              mesh.area());
  std::printf("evaluation against the scene: coverage %.1f %%, error mean %.2f cm, std %.2f cm, RMSE %.2f cm\n",
              100.0 * eval.coverage.coverage(), 100.0 * eval.error_stats.mean, 100.0 * eval.error_stats.std_dev,
              100.0 * eval.error_stats.rmse);
  std::printf("wrote %s/report.json, report.md, scene.ply, reconstruction.ply, map.tsdf and depth_*.png\n",
              out_dir.c_str());
  return seeing > 0 ? 0 : 1;
}
