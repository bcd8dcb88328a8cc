// Incomplete-surface stage on the shared power plant (../shared/scenes/
// powerplant.dae, scaled by 0.656, clipped at z = 15 m) mapped at 0.3 m by a
// scripted survey flight (three loops at 3, 8 and 13 m, 3 m standoff, a
// depth frame every metre): ISE extraction, full and incremental (one
// integrated frame at a time), and the whole frontier update with its
// stages (viewpoints, merging, visibility ray casting, clusters), with 1 and
// 2 threads. The last frames of the flight are held out and integrated one by
// one for the incremental figures; every benchmark starts from the same map.
// Counters: ISEs, C_rem, viewpoints before / after merging, clusters,
// blocks re-read / re-examined per frame, DDA voxel steps per second.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/map_io.h"
#include "surface_nbv/map/tsdf_integrator.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/scene_source.h"
#include "surface_nbv/sim/scripted_flight.h"
#include "surface_nbv/surface/frontier_builder.h"

using namespace surface_nbv;

namespace {

// Frames kept for the incremental figures: one in kHeldOutEvery, at most kHeldOut.
constexpr int kHeldOut = 40;
constexpr int kHeldOutEvery = 16;

struct Survey {
  CameraConfig camera;
  TsdfConfig config;
  std::string map_file;                // the map after the flight less the held-out frames
  std::vector<Transform> held_poses;   // T_W_C of the held-out frames
  std::vector<DepthImage> held_depths;
  ~Survey() {
    std::error_code ec;
    std::filesystem::remove(map_file, ec);
  }
};

void fail(const std::string& message) {
  std::fprintf(stderr, "bench_surface: %s\n", message.c_str());
  std::exit(2);
}

const Survey& survey() {
  static std::unique_ptr<Survey> cached;
  if (cached) return *cached;
  cached = std::make_unique<Survey>();
  Survey& s = *cached;
  SceneConfig scene_config;
  scene_config.scene = std::string(NBV_SOURCE_DIR) + "/../shared/scenes/powerplant.dae";
  scene_config.transform.scale = 0.656;
  scene_config.transform.crop.max.z() = 15.0;
  TriangleMesh mesh;
  std::unique_ptr<RaycastScene> scene;
  if (Status st = loadScene(scene_config, &mesh); !st) fail(st.message());
  if (Status st = RaycastScene::create(mesh, &scene); !st) fail(st.message());
  const DepthCamera camera(s.camera);
  const DepthRenderer renderer(*scene, camera, 2);
  // config/powerplant.yaml: the flight's target box, standoff and altitudes.
  FlightConfig flight_config;
  flight_config.target = AlignedBox(Eigen::Vector3d(-34.5, -19.2, 0.0), Eigen::Vector3d(30.6, 23.3, 15.0));
  flight_config.standoff = 3.0;
  flight_config.altitudes = {3.0, 8.0, 13.0};
  const ScriptedFlight flight(flight_config);
  const AlignedBox b = mesh.bounds();
  s.config.voxel_size = 0.3;
  s.config.threads = 2;
  s.config.bounds = AlignedBox(b.min - Eigen::Vector3d(5, 5, 0), b.max + Eigen::Vector3d(5, 5, 2));
  s.config.bounds.min.z() = std::min(b.min.z(), 0.0) - 0.6;
  TsdfMap map(s.config);
  TsdfIntegrator integrator(&map);
  const int frames = static_cast<int>(flight.length()) + 1;
  for (int i = 0; i < frames; ++i) {
    const Transform T_W_C = flight.poseAtDistance(std::min<double>(i, flight.length())) * opticalInBody();
    DepthImage depth;
    renderer.render(T_W_C, &depth, static_cast<uint64_t>(i));
    if (i % kHeldOutEvery == kHeldOutEvery / 2 && static_cast<int>(s.held_poses.size()) < kHeldOut) {
      s.held_poses.push_back(T_W_C);
      s.held_depths.push_back(std::move(depth));
    } else if (Status st = integrator.integrateDepth(camera, depth, T_W_C); !st) {
      fail(st.message());
    }
  }
  s.map_file = (std::filesystem::temp_directory_path() / ("bench_surface_" + std::to_string(getpid()) + ".tsdf")).string();
  if (Status st = saveMap(map, s.map_file); !st) fail(st.message());
  std::printf("power plant: %zu triangles, %.0f m flight, %d frames (%d held out), map %d x %d x %d voxels, %zu blocks\n",
              mesh.numTriangles(), flight.length(), frames, kHeldOut, map.gridVoxels().x(), map.gridVoxels().y(),
              map.gridVoxels().z(), map.numBlocks());
  return s;
}

std::unique_ptr<TsdfMap> loadSurveyMap() {
  const Survey& s = survey();
  auto map = std::make_unique<TsdfMap>(s.config);
  if (Status st = loadMap(s.map_file, map.get()); !st) fail(st.message());
  return map;
}

SurfaceConfig surfaceConfig(int threads) {
  SurfaceConfig c;
  c.camera = survey().camera;
  c.threads = threads;
  return c;
}

// Integrates held-out frame i (cycling).
void integrateHeldOut(size_t i, TsdfMap* map) {
  const Survey& s = survey();
  TsdfIntegrator integrator(map);
  const DepthCamera camera(s.camera);
  integrator.integrateDepth(camera, s.held_depths[i % s.held_depths.size()], s.held_poses[i % s.held_poses.size()]);
}

void reportFrontier(benchmark::State& state, const Frontier& f) {
  state.counters["ISEs"] = static_cast<double>(f.ises.size());
  state.counters["C_rem"] = static_cast<double>(f.remaining);
  state.counters["poses"] = static_cast<double>(f.stats.unmerged_viewpoints);
  state.counters["viewpoints"] = static_cast<double>(f.viewpoints.size());
  state.counters["clusters"] = static_cast<double>(f.clusters.size());
}

void BM_IseFull(benchmark::State& state) {
  const auto map = loadSurveyMap();
  IseExtractor extractor(static_cast<int>(state.range(0)));
  for (auto _ : state) extractor.rebuild(*map);
  state.counters["ISEs"] = static_cast<double>(extractor.size());
  state.counters["scanned"] = static_cast<double>(extractor.scannedCount());
  state.counters["blocks"] = static_cast<double>(map->numBlocks());
}

void BM_IseIncremental(benchmark::State& state) {
  const auto map = loadSurveyMap();
  IseExtractor extractor(static_cast<int>(state.range(0)));
  extractor.update(*map);
  size_t frame = 0, changed = 0, examined = 0;
  for (auto _ : state) {
    state.PauseTiming();
    integrateHeldOut(frame++, map.get());
    state.ResumeTiming();
    const IseUpdateStats stats = extractor.update(*map);
    changed += stats.blocks_changed;
    examined += stats.blocks_examined;
  }
  state.counters["ISEs"] = static_cast<double>(extractor.size());
  state.counters["changed_blocks"] = static_cast<double>(changed) / frame;
  state.counters["examined_blocks"] = static_cast<double>(examined) / frame;
}

// The whole update after a full re-extraction (reset before each one).
void BM_FrontierFull(benchmark::State& state) {
  const auto map = loadSurveyMap();
  const CollisionMap collision(*map, CollisionConfig());
  FrontierBuilder builder(surfaceConfig(static_cast<int>(state.range(0))));
  Frontier f;
  for (auto _ : state) {
    builder.reset();
    if (Status st = builder.update(*map, collision, &f); !st) fail(st.message());
  }
  reportFrontier(state, f);
}

// The whole update after one integrated frame (the collision map's own
// update is timed apart: collision_ms).
void BM_FrontierIncremental(benchmark::State& state) {
  const auto map = loadSurveyMap();
  CollisionMap collision(*map, CollisionConfig());
  FrontierBuilder builder(surfaceConfig(static_cast<int>(state.range(0))));
  Frontier f;
  builder.update(*map, collision, &f);
  size_t frame = 0;
  double collision_ms = 0.0, ise_ms = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    integrateHeldOut(frame++, map.get());
    const auto t0 = std::chrono::steady_clock::now();
    collision.update(*map);
    collision_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    state.ResumeTiming();
    if (Status st = builder.update(*map, collision, &f); !st) fail(st.message());
    ise_ms += f.stats.ise_ms;
  }
  reportFrontier(state, f);
  state.counters["collision_ms"] = collision_ms / frame;
  state.counters["ise_ms"] = ise_ms / frame;
}

// One stage of the update, timed by the builder (manual time). Arg 0: stage.
void BM_Stage(benchmark::State& state) {
  const auto map = loadSurveyMap();
  const CollisionMap collision(*map, CollisionConfig());
  FrontierBuilder builder(surfaceConfig(static_cast<int>(state.range(1))));
  Frontier f;
  builder.update(*map, collision, &f);
  uint64_t steps = 0;
  double visibility_ms = 0.0;
  for (auto _ : state) {
    builder.update(*map, collision, &f);
    const FrontierStats& s = f.stats;
    const double ms[] = {s.viewpoints_ms, s.merge_ms, s.visibility_ms, s.clusters_ms};
    state.SetIterationTime(ms[state.range(0)] * 1e-3);
    steps += s.voxel_steps;
    visibility_ms += s.visibility_ms;
  }
  reportFrontier(state, f);
  if (state.range(0) == 2) {
    state.counters["Msteps_per_s"] = steps / (visibility_ms * 1e-3) / 1e6;
    state.counters["steps_per_view"] = static_cast<double>(f.stats.voxel_steps) / std::max<size_t>(f.viewpoints.size(), 1);
  }
  if (state.range(0) == 3) state.counters["links"] = static_cast<double>(f.stats.links);
}

void threads(benchmark::internal::Benchmark* b) {
  b->ArgNames({"threads"})->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
}

void stages(benchmark::internal::Benchmark* b) {
  b->ArgNames({"stage", "threads"});
  for (int stage = 0; stage < 4; ++stage) {
    for (int t : {1, 2}) b->Args({stage, t});
  }
  b->Unit(benchmark::kMillisecond)->UseManualTime();
}

}  // namespace

BENCHMARK(BM_IseFull)->Apply(threads);
BENCHMARK(BM_IseIncremental)->Apply(threads);
BENCHMARK(BM_FrontierFull)->Apply(threads);
BENCHMARK(BM_FrontierIncremental)->Apply(threads);
// stage: 0 viewpoints (eq. 2, fall-backs, C_rem), 1 merging, 2 visibility, 3 clusters and gains.
BENCHMARK(BM_Stage)->Apply(stages);

BENCHMARK_MAIN();
