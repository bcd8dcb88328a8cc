// Depth rendering speed: 640 x 480 frames of the built-in `plant` and of the
// shared power plant (scaled and clipped as in the paper) with 1 and 2
// threads, from poses along the scripted flight. Reports rays per second.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/scene_source.h"
#include "surface_nbv/sim/scripted_flight.h"

using namespace surface_nbv;

namespace {

struct LoadedScene {
  TriangleMesh mesh;
  std::unique_ptr<RaycastScene> scene;
  std::vector<Transform> poses;
};

std::string powerplantPath() { return std::string(NBV_SOURCE_DIR) + "/../shared/scenes/powerplant.dae"; }

const LoadedScene* getScene(const std::string& name) {
  static std::map<std::string, std::unique_ptr<LoadedScene>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second.get();
  auto loaded = std::make_unique<LoadedScene>();
  SceneConfig config;
  config.scene = name;
  if (name == "powerplant") {
    config.scene = powerplantPath();
    config.transform.scale = 0.656;
    config.transform.crop.max.z() = 15.0;
  }
  if (!loadScene(config, &loaded->mesh) || !RaycastScene::create(loaded->mesh, &loaded->scene)) {
    cache[name] = nullptr;
    return nullptr;
  }
  const ScriptedFlight flight(flightAround(loaded->mesh.bounds(), 5.0, 2, 0.5));
  for (int i = 0; i < 64; ++i) loaded->poses.push_back(flight.poseAtDistance(flight.length() * i / 64.0) * opticalInBody());
  return (cache[name] = std::move(loaded)).get();
}

void BM_RenderDepth(benchmark::State& state, const std::string& name) {
  const LoadedScene* s = getScene(name);
  if (s == nullptr) {
    state.SkipWithError(("scene " + name + " not available").c_str());
    return;
  }
  CameraConfig config;  // 640 x 480, 90 x 60 deg, [1.6, 8] m
  const DepthCamera camera(config);
  const DepthRenderer renderer(*s->scene, camera, static_cast<int>(state.range(0)));
  DepthImage depth;
  size_t i = 0, valid = 0;
  for (auto _ : state) {
    renderer.render(s->poses[i++ % s->poses.size()], &depth);
    valid += depth.validCount();
    benchmark::DoNotOptimize(depth.data.data());
  }
  const double rays = static_cast<double>(state.iterations()) * config.width * config.height;
  state.counters["rays_per_s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
  state.counters["valid_px"] = static_cast<double>(valid) / state.iterations();
  state.counters["triangles"] = static_cast<double>(s->mesh.numTriangles());
}

}  // namespace

BENCHMARK_CAPTURE(BM_RenderDepth, plant, std::string("plant"))->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RenderDepth, powerplant, std::string("powerplant"))
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_RenderDepth, statue, std::string("statue"))->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
