// Depth rendering speed: 640 x 480 frames of the built-in `plant` and of the
// shared power plant (scaled and clipped as in the paper) with 1 and 2
// threads, from poses along the scripted flight. Reports rays per second.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "surface_nbv/sim/depth_renderer.h"
#include "bench_scenes.h"
#include "surface_nbv/sim/scripted_flight.h"

using namespace surface_nbv;

namespace {

struct LoadedScene {
  TriangleMesh mesh;
  std::unique_ptr<RaycastScene> scene;
  std::vector<Transform> poses;        // along the flight, some looking past the structure
  std::vector<Transform> dense_poses;  // those that see it in at least 40 % of the pixels
};


const LoadedScene* getScene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<LoadedScene>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second.get();
  auto loaded = std::make_unique<LoadedScene>();
  const SceneConfig config = benchSceneConfig(name);
  if (!loadScene(config, &loaded->mesh) || !RaycastScene::create(loaded->mesh, &loaded->scene)) {
    cache[name] = nullptr;
    return nullptr;
  }
  const ScriptedFlight flight(flightAround(loaded->mesh.bounds(), 3.0, 3, 0.5));
  const DepthCamera camera{CameraConfig()};
  const DepthRenderer renderer(*loaded->scene, camera, 2);
  DepthImage depth;
  for (int i = 0; i < 256; ++i) {
    const Transform T_W_C = flight.poseAtDistance(flight.length() * i / 256.0) * opticalInBody();
    if (i % 4 == 0) loaded->poses.push_back(T_W_C);
    renderer.render(T_W_C, &depth);
    if (depth.validCount() >= 0.4 * depth.data.size()) loaded->dense_poses.push_back(T_W_C);
  }
  std::printf("scene %s: %zu triangles, %zu flight poses, %zu dense poses; native packet %d rays\n", name.c_str(),
              loaded->mesh.numTriangles(), loaded->poses.size(), loaded->dense_poses.size(),
              loaded->scene->nativePacketWidth());
  return (cache[name] = std::move(loaded)).get();
}

// Poses for a benchmark: range(1) == 1 selects the dense ones.
const std::vector<Transform>* posesFor(benchmark::State& state, const std::string& name, const LoadedScene** out) {
  const LoadedScene* s = getScene(name);
  *out = s;
  if (s == nullptr) {
    state.SkipWithError(("scene " + name + " not available").c_str());
    return nullptr;
  }
  const std::vector<Transform>* poses = state.range(1) == 1 ? &s->dense_poses : &s->poses;
  if (poses->empty()) {
    state.SkipWithError("no pose");
    return nullptr;
  }
  return poses;
}

void setCounters(benchmark::State& state, const LoadedScene* s, const CameraConfig& config, size_t valid) {
  const double rays = static_cast<double>(state.iterations()) * config.width * config.height;
  state.counters["rays_per_s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
  state.counters["valid_px"] = static_cast<double>(valid) / state.iterations();
  state.counters["triangles"] = static_cast<double>(s->mesh.numTriangles());
}

// Args: {threads, dense, packet}: packets of 4, 8 or 16 rays (the renderer's
// default is the widest the CPU traces natively, printed with the scene).
void BM_RenderDepth(benchmark::State& state, const std::string& name) {
  const LoadedScene* s = nullptr;
  const std::vector<Transform>* poses = posesFor(state, name, &s);
  if (poses == nullptr) return;
  CameraConfig config;  // 640 x 480, 90 x 60 deg, [1.6, 8] m
  const DepthCamera camera(config);
  const DepthRenderer renderer(*s->scene, camera, static_cast<int>(state.range(0)), static_cast<int>(state.range(2)));
  DepthImage depth;
  size_t i = 0, valid = 0;
  for (auto _ : state) {
    renderer.render((*poses)[i++ % poses->size()], &depth);
    valid += depth.validCount();
    benchmark::DoNotOptimize(depth.data.data());
  }
  setCounters(state, s, config, valid);
}

// The same frames cast one ray at a time (rtcIntersect1), one thread: the
// baseline the packet renderer is measured against.
void BM_RenderDepthSingleRays(benchmark::State& state, const std::string& name) {
  const LoadedScene* s = nullptr;
  const std::vector<Transform>* poses = posesFor(state, name, &s);
  if (poses == nullptr) return;
  CameraConfig config;
  const DepthCamera camera(config);
  std::vector<float> depth(static_cast<size_t>(config.width) * config.height);
  size_t i = 0, valid = 0;
  for (auto _ : state) {
    const Transform& T_W_C = (*poses)[i++ % poses->size()];
    for (int r = 0; r < config.height; ++r) {
      for (int c = 0; c < config.width; ++c) {
        double t;
        const bool hit = s->scene->intersect(T_W_C.translation(), T_W_C.linear() * camera.pixelRay(c, r), 0.0,
                                             config.max_range, &t);
        const bool ok = hit && camera.depthInRange(t);
        depth[static_cast<size_t>(r) * config.width + c] = ok ? static_cast<float>(t) : NAN;
        valid += ok ? 1 : 0;
      }
    }
    benchmark::DoNotOptimize(depth.data());
  }
  setCounters(state, s, config, valid);
}

}  // namespace

#define NBV_RENDER_BENCH(scene)                                                                          \
  BENCHMARK_CAPTURE(BM_RenderDepth, scene, std::string(#scene))                                          \
      ->ArgNames({"threads", "dense", "packet"})                                                         \
      ->ArgsProduct({{1, 2}, {0, 1}, {4, 8, 16}})                                                        \
      ->Unit(benchmark::kMillisecond)                                                                    \
      ->UseRealTime();                                                                                   \
  BENCHMARK_CAPTURE(BM_RenderDepthSingleRays, scene, std::string(#scene))                                \
      ->ArgNames({"threads", "dense"})                                                                   \
      ->Args({1, 1})                                                                                     \
      ->Unit(benchmark::kMillisecond)                                                                    \
      ->UseRealTime()

NBV_RENDER_BENCH(plant);
NBV_RENDER_BENCH(powerplant);
NBV_RENDER_BENCH(statue);

BENCHMARK_MAIN();
