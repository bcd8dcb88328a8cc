// Evaluation time: a ground truth evaluated against itself at 0.3 m voxels
// (samples every 0.1 m, pruning, coverage, M3C2), 1 and 2 threads. The
// shared power plant is loaded as in the paper (scale 0.656, clipped at
// z = 15 m) and skipped with a message when the file is absent; the built-in
// plant always runs. Target: under 30 s for the power plant on 2 cores.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "surface_nbv/eval/evaluator.h"
#include "bench_scenes.h"

using namespace surface_nbv;

namespace {


// nullptr when the scene cannot be loaded (message printed once).
const TriangleMesh* sceneMesh(const std::string& name) {
  static std::map<std::string, std::unique_ptr<TriangleMesh>> cache;
  if (auto it = cache.find(name); it != cache.end()) return it->second.get();
  const SceneConfig config = benchSceneConfig(name);
  auto mesh = std::make_unique<TriangleMesh>();
  if (Status s = loadScene(config, mesh.get()); !s) {
    std::printf("scene %s skipped: %s\n", name.c_str(), s.message().c_str());
    mesh.reset();
  }
  return (cache[name] = std::move(mesh)).get();
}

void evaluateItself(benchmark::State& state, const std::string& name) {
  const TriangleMesh* mesh = sceneMesh(name);
  if (mesh == nullptr) {
    state.SkipWithError((name + " not available (" + powerplantPath() + ")").c_str());
    return;
  }
  EvalConfig config;
  config.voxel_size = 0.3;
  config.threads = static_cast<int>(state.range(0));
  EvalResult result;
  for (auto _ : state) {
    if (Status s = Evaluator(config).evaluate(*mesh, *mesh, &result); !s) {
      state.SkipWithError(s.message().c_str());
      return;
    }
  }
  const EvalTimings& t = result.timings;
  state.counters["samples"] = static_cast<double>(result.ground_truth.size());
  state.counters["visible"] = static_cast<double>(result.numVisible());
  state.counters["coverage"] = result.coverage.coverage();
  state.counters["rmse_m"] = result.error_stats.rmse;
  state.counters["sample_s"] = t.sample_s;
  state.counters["free_space_s"] = t.free_space_s;
  state.counters["visibility_s"] = t.visibility_s;
  state.counters["coverage_s"] = t.coverage_s;
  state.counters["m3c2_s"] = t.m3c2_s;
}

void BM_EvaluatePowerplant(benchmark::State& state) { evaluateItself(state, "powerplant"); }
void BM_EvaluatePlant(benchmark::State& state) { evaluateItself(state, "plant"); }

}  // namespace

BENCHMARK(BM_EvaluatePowerplant)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_EvaluatePlant)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

BENCHMARK_MAIN();
