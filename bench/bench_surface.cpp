// Incomplete-surface stage on the shared power plant (../shared/scenes/
// powerplant.dae, scaled by 0.656, clipped at z = 15 m), mapped at 0.3 m by a
// scripted survey flight (loops at 3, 8 and 13 m around the plant's box).
// Settings (first argument):
//   0 paper:  config/powerplant.yaml as shipped: 8 m camera, 3 m standoff,
//             pixels without return ignored by the mapper.
//   1 stress: a 30 m camera from 10 m out, pixels without return clearing
//             free space, then half of the occupied voxels forgotten (holes
//             in the scanned surfaces, seeded): tens of thousands of ISEs.
// Frames are rendered every 0.5 m (stress: 1 m) and their weights scaled to
// what a 30 Hz camera at 0.5 m/s would accumulate; the surface stage always
// uses the paper's 8 m camera. One frame in 16 (at most 40) is held out and
// integrated one at a time for the incremental figures; every benchmark
// starts from the same map. Stages: ISE extraction (full, incremental), the
// whole frontier update (full, after one frame), viewpoints (eq. 2,
// fall-backs, C_rem), merging, visibility (DDA voxel steps per second) and
// clusters with gains, with 1 and 2 threads.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "bench_scenes.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/map_io.h"
#include "surface_nbv/map/tsdf_integrator.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/scene_source.h"
#include "surface_nbv/sim/scripted_flight.h"
#include "surface_nbv/surface/frontier_builder.h"

using namespace surface_nbv;

namespace {

struct Setting {
  const char* name;
  double range, standoff, step;  // camera max range, flight standoff, metres between rendered frames
  bool clear_invalid;            // pixels without return clear free space
  double forget;                 // fraction of occupied voxels made unknown after the flight
};
const Setting kSettings[] = {{"paper", 8.0, 3.0, 0.5, false, 0.0}, {"stress", 30.0, 10.0, 1.0, true, 0.5}};
constexpr int kHeldOut = 40;
constexpr int kHeldOutEvery = 16;
constexpr double kFrameSpacing = 0.5 / 30.0;  // metres between frames at 0.5 m/s and 30 Hz

struct Survey {
  CameraConfig camera;  // the survey's camera
  TsdfConfig config;
  std::string map_file;  // the map after the flight, less the held-out frames
  std::vector<Transform> held_poses;
  std::vector<DepthImage> held_depths;
  ~Survey() {
    std::error_code ec;
    std::filesystem::remove(map_file, ec);
  }
};

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "bench_surface: %s\n", message.c_str());
  std::exit(2);
}

// A uniform number in [0, 1) from a voxel's block and position.
double voxelHash(const Eigen::Vector3i& block, int voxel) {
  uint64_t h = 0x9E3779B97F4A7C15ull;
  for (uint64_t v : {static_cast<uint64_t>(block.x()), static_cast<uint64_t>(block.y()),
                     static_cast<uint64_t>(block.z()), static_cast<uint64_t>(voxel)}) {
    h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 31;
  }
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

const Survey& survey(int setting) {
  static std::map<int, std::unique_ptr<Survey>> cache;
  std::unique_ptr<Survey>& slot = cache[setting];
  if (slot) return *slot;
  slot = std::make_unique<Survey>();
  Survey& s = *slot;
  const Setting& set = kSettings[setting];
  const auto t0 = std::chrono::steady_clock::now();
  const SceneConfig scene_config = benchSceneConfig("powerplant");
  TriangleMesh mesh;
  std::unique_ptr<RaycastScene> scene;
  if (Status st = loadScene(scene_config, &mesh); !st) fail(st.message());
  if (Status st = RaycastScene::create(mesh, &scene); !st) fail(st.message());
  s.camera.max_range = set.range;
  const DepthCamera camera(s.camera);
  const DepthRenderer renderer(*scene, camera, 2);
  // config/powerplant.yaml: the flight's target box and altitudes.
  FlightConfig flight_config;
  flight_config.target = AlignedBox(Eigen::Vector3d(-34.5, -19.2, 0.0), Eigen::Vector3d(30.6, 23.3, 15.0));
  flight_config.standoff = set.standoff;
  flight_config.altitudes = {3.0, 8.0, 13.0};
  const ScriptedFlight flight(flight_config);
  const AlignedBox b = mesh.bounds();
  const double margin = std::max(5.0, set.standoff + 2.0);
  s.config.voxel_size = 0.3;
  s.config.threads = 2;
  s.config.invalid_pixels = set.clear_invalid ? InvalidPixelPolicy::kClearToMaxRange : InvalidPixelPolicy::kIgnore;
  s.config.bounds = AlignedBox(b.min - Eigen::Vector3d(margin, margin, 0), b.max + Eigen::Vector3d(margin, margin, 2));
  s.config.bounds.min.z() = std::min(b.min.z(), 0.0) - 0.6;
  TsdfMap map(s.config);
  TsdfIntegrator integrator(&map);
  const int frames = static_cast<int>(flight.length() / set.step) + 1;
  for (int i = 0; i < frames; ++i) {
    const Transform T_W_C = flight.poseAtDistance(std::min(flight.length(), i * set.step)) * opticalInBody();
    DepthImage depth;
    renderer.render(T_W_C, &depth, static_cast<uint64_t>(i));
    if (i % kHeldOutEvery == kHeldOutEvery / 2 && static_cast<int>(s.held_poses.size()) < kHeldOut) {
      s.held_poses.push_back(T_W_C);
      s.held_depths.push_back(std::move(depth));
    } else if (Status st = integrator.integrateDepth(camera, depth, T_W_C); !st) {
      fail(st.message());
    }
  }
  const float weight_scale = static_cast<float>(set.step / kFrameSpacing);
  size_t forgotten = 0;
  for (const auto& block : map.blocks()) {
    for (int k = 0; k < kBlockVoxels; ++k) {
      TsdfVoxel& v = block->voxels[k];
      v.w *= weight_scale;
      if (set.forget > 0.0 && map.stateOf(v) == VoxelState::kOccupied && voxelHash(block->index, k) < set.forget) {
        v.w = 0.0f;
        ++forgotten;
      }
    }
  }
  s.map_file = (std::filesystem::temp_directory_path() /
                ("bench_surface_" + std::to_string(getpid()) + "_" + set.name + ".tsdf")).string();
  if (Status st = saveMap(map, s.map_file); !st) fail(st.message());
  std::printf("%s: %.0f m flight, %d frames (%zu held out), map %d x %d x %d voxels, %zu blocks, %zu occupied "
              "voxels forgotten, built in %.0f s\n",
              set.name, flight.length(), frames, s.held_poses.size(), map.gridVoxels().x(), map.gridVoxels().y(),
              map.gridVoxels().z(), map.numBlocks(), forgotten,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  std::fflush(stdout);
  return s;
}

std::unique_ptr<TsdfMap> loadSurveyMap(int setting) {
  const Survey& s = survey(setting);
  auto map = std::make_unique<TsdfMap>(s.config);
  if (Status st = loadMap(s.map_file, map.get()); !st) fail(st.message());
  return map;
}

SurfaceConfig surfaceConfig(int threads) {
  SurfaceConfig c;  // the paper's camera (8 m), whatever the survey's
  c.threads = threads;
  return c;
}

void integrateHeldOut(int setting, size_t i, TsdfMap* map) {
  const Survey& s = survey(setting);
  TsdfIntegrator integrator(map);
  const DepthCamera camera(s.camera);
  const size_t k = i % s.held_poses.size();
  if (Status st = integrator.integrateDepth(camera, s.held_depths[k], s.held_poses[k]); !st) fail(st.message());
}

void reportFrontier(benchmark::State& state, const Frontier& f) {
  state.counters["ISEs"] = static_cast<double>(f.ises.size());
  state.counters["C_rem"] = static_cast<double>(f.remaining);
  state.counters["C_rem_unknown"] = static_cast<double>(f.remaining_unknown);
  state.counters["poses"] = static_cast<double>(f.stats.unmerged_viewpoints);
  state.counters["viewpoints"] = static_cast<double>(f.viewpoints.size());
  state.counters["clusters"] = static_cast<double>(f.clusters.size());
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Args: {setting, threads}.
void BM_IseFull(benchmark::State& state) {
  const auto map = loadSurveyMap(static_cast<int>(state.range(0)));
  IseExtractor extractor(static_cast<int>(state.range(1)));
  for (auto _ : state) extractor.rebuild(*map);
  state.counters["ISEs"] = static_cast<double>(extractor.size());
  state.counters["scanned"] = static_cast<double>(extractor.scannedCount());
  state.counters["blocks"] = static_cast<double>(map->numBlocks());
}

void BM_IseIncremental(benchmark::State& state) {
  const int setting = static_cast<int>(state.range(0));
  const auto map = loadSurveyMap(setting);
  IseExtractor extractor(static_cast<int>(state.range(1)));
  extractor.update(*map);
  size_t frame = 0, changed = 0, examined = 0;
  for (auto _ : state) {
    state.PauseTiming();
    integrateHeldOut(setting, frame++, map.get());
    state.ResumeTiming();
    const IseUpdateStats stats = extractor.update(*map);
    changed += stats.blocks_changed;
    examined += stats.blocks_examined;
  }
  state.counters["ISEs"] = static_cast<double>(extractor.size());
  state.counters["changed_blocks"] = static_cast<double>(changed) / static_cast<double>(frame);
  state.counters["examined_blocks"] = static_cast<double>(examined) / static_cast<double>(frame);
}

// The whole update with a full re-extraction (reset before each one).
void BM_FrontierFull(benchmark::State& state) {
  const auto map = loadSurveyMap(static_cast<int>(state.range(0)));
  const CollisionMap collision(*map, CollisionConfig());
  FrontierBuilder builder(surfaceConfig(static_cast<int>(state.range(1))));
  Frontier f;
  for (auto _ : state) {
    builder.reset();
    if (Status st = builder.update(*map, collision, &f); !st) fail(st.message());
  }
  reportFrontier(state, f);
}

// The whole update after one integrated frame; the collision map's own
// update runs untimed before it and is reported as collision_ms.
void BM_FrontierIncremental(benchmark::State& state) {
  const int setting = static_cast<int>(state.range(0));
  const auto map = loadSurveyMap(setting);
  CollisionMap collision(*map, CollisionConfig());
  FrontierBuilder builder(surfaceConfig(static_cast<int>(state.range(1))));
  Frontier f;
  if (Status st = builder.update(*map, collision, &f); !st) fail(st.message());
  size_t frame = 0;
  double collision_ms = 0.0, ise_ms = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    integrateHeldOut(setting, frame++, map.get());
    const auto t0 = std::chrono::steady_clock::now();
    collision.update(*map);
    collision_ms += msSince(t0);
    state.ResumeTiming();
    if (Status st = builder.update(*map, collision, &f); !st) fail(st.message());
    ise_ms += f.stats.ise_ms;
  }
  reportFrontier(state, f);
  state.counters["collision_ms"] = collision_ms / static_cast<double>(frame);
  state.counters["ise_ms"] = ise_ms / static_cast<double>(frame);
}

// Ray casting alone: C_q of every viewpoint of the map's frontier.
void BM_Visibility(benchmark::State& state) {
  const auto map = loadSurveyMap(static_cast<int>(state.range(0)));
  const CollisionMap collision(*map, CollisionConfig());
  const SurfaceConfig config = surfaceConfig(static_cast<int>(state.range(1)));
  FrontierBuilder builder(config);
  Frontier f;
  if (Status st = builder.update(*map, collision, &f); !st) fail(st.message());
  const VoxelRayCaster rays(builder.extractor().states(), config.unknown_blocks_visibility);
  const VisibilityEvaluator visibility(config);
  uint64_t steps = 0;
  for (auto _ : state) steps += visibility.evaluate(rays, f.ises, &f.viewpoints);
  state.counters["voxel_steps"] = benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["steps_per_view"] = static_cast<double>(steps) / state.iterations() / f.viewpoints.size();
  reportFrontier(state, f);
}

// One stage of the update as the builder times it (manual time).
// Args: {stage, setting, threads}; stage 0 viewpoints, 1 merging, 2 clusters.
void BM_Stage(benchmark::State& state) {
  const auto map = loadSurveyMap(static_cast<int>(state.range(1)));
  const CollisionMap collision(*map, CollisionConfig());
  FrontierBuilder builder(surfaceConfig(static_cast<int>(state.range(2))));
  Frontier f;
  for (auto _ : state) {
    if (Status st = builder.update(*map, collision, &f); !st) fail(st.message());
    const double ms[] = {f.stats.viewpoints_ms, f.stats.merge_ms, f.stats.clusters_ms};
    state.SetIterationTime(ms[state.range(0)] * 1e-3);
  }
  reportFrontier(state, f);
  state.counters["poses_tested"] = static_cast<double>(f.stats.poses_tested);
  state.counters["links"] = static_cast<double>(f.stats.links);
}

void settingsAndThreads(benchmark::internal::Benchmark* b) {
  b->ArgNames({"setting", "threads"});
  for (int s = 0; s < 2; ++s) {
    for (int t : {1, 2}) b->Args({s, t});
  }
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

void stages(benchmark::internal::Benchmark* b) {
  b->ArgNames({"stage", "setting", "threads"});
  for (int stage = 0; stage < 3; ++stage) {
    for (int s = 0; s < 2; ++s) {
      for (int t : {1, 2}) b->Args({stage, s, t});
    }
  }
  // Each iteration runs the whole update to time one stage: a fixed count.
  b->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(10);
}

}  // namespace

BENCHMARK(BM_IseFull)->Apply(settingsAndThreads);
BENCHMARK(BM_IseIncremental)->Apply(settingsAndThreads);
BENCHMARK(BM_FrontierFull)->Apply(settingsAndThreads);
BENCHMARK(BM_FrontierIncremental)->Apply(settingsAndThreads);
BENCHMARK(BM_Visibility)->Apply(settingsAndThreads);
BENCHMARK(BM_Stage)->Apply(stages);

BENCHMARK_MAIN();
