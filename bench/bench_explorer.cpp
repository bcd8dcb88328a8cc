// Planning latency per stage on a power-plant-sized frontier: the shared power
// plant (config/powerplant.yaml) explored headless for `kFlight` seconds of
// flight, then, on that map and its frontier:
//   BM_FullRecompute   the cluster graph (eq. 4, 5), the LK tour and the first
//                      leg with a fresh roadmap (what a full recomputation costs),
//                      argument 1: cluster-graph distances by the path-length
//                      oracle (path_distances) on a roadmap warmed by 150 queries
//   BM_LocalUpdate     a local update (one cluster covered, tour kept) and the leg
//   BM_PathQuery       a LazyPRM* query between two connected frontier viewpoints
//                      on a roadmap kept from earlier queries; arguments:
//                      shortcutting on/off, and PathPlannerConfig::search
//   BM_RoadmapEdges    PathPlanner::roadmapEdges(20000), what nbv_planner's
//                      roadmap marker copies out of OMPL, after N path queries
//                      between frontier viewpoints (argument N)
//   BM_ReachableFill   ReachableSpace::fill from the UAV at the planner's
//                      clearance, what the explorer does once per map version
// Counters give the stage split (ms) and the frontier's size; BM_PathQuery
// also the median query (median_ms) and the roadmap's size.
//   scripts/bench explorer
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <memory>

#include "bench_scenes.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/mission/mission_runner.h"
#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/planning/reachable_space.h"
#include "surface_nbv/surface/frontier_builder.h"

using namespace surface_nbv;

namespace {

constexpr double kFlight = 480.0;

struct World {
  MissionConfig config;
  std::unique_ptr<RaycastScene> scene;
  std::unique_ptr<MissionRunner> runner;
  std::unique_ptr<CollisionMap> collision;
  Frontier frontier;
  Eigen::Vector4d uav = Eigen::Vector4d::Zero();
  bool ok = false;
};

World& world() {
  static World w = [] {
    World w;
    if (!loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/powerplant.yaml", &w.config)) return w;
    w.config.scene = benchSceneConfig("powerplant");
    w.config.max_flight_time = kFlight;
    w.config.progress_period = 1e9;
    TriangleMesh mesh;
    if (!loadScene(w.config.scene, &mesh) || !RaycastScene::create(mesh, &w.scene)) return w;
    std::fprintf(stderr, "bench_explorer: exploring the power plant for %.0f s of flight...\n", kFlight);
    w.runner = std::make_unique<MissionRunner>(w.config, *w.scene);
    const MissionResult r = w.runner->run();
    if (!r.status || r.flown.empty()) {
      std::fprintf(stderr, "bench_explorer: mission failed: %s\n", r.status.message().c_str());
      return w;
    }
    w.uav = r.flown.back();
    w.collision = std::make_unique<CollisionMap>(w.runner->map(), w.config.collision);
    SurfaceConfig surface = w.config.surface;
    surface.threads = 1;
    FrontierBuilder builder(surface);
    if (!builder.update(w.runner->map(), *w.collision, &w.frontier)) return w;
    std::fprintf(stderr, "bench_explorer: %.0f m flown; frontier: %zu ISEs (%zu in C_ins), %zu viewpoints, %zu clusters\n",
                 r.path_length, w.frontier.ises.size(), w.frontier.insideCount(), w.frontier.viewpoints.size(),
                 w.frontier.clusters.size());
    w.ok = true;
    return w;
  }();
  return w;
}

void setCounters(benchmark::State& state, const ExplorerTimings& t, size_t n) {
  const World& w = world();
  state.counters["graph_ms"] = t.graph_ms / n;
  state.counters["tour_ms"] = t.tour_ms / n;
  state.counters["path_ms"] = t.path_ms / n;
  state.counters["viewpoints"] = w.frontier.viewpoints.size();
  state.counters["clusters"] = w.frontier.clusters.size();
}

// Warms a planner's roadmap with one pass of queries between consecutive
// frontier viewpoints, as a mission does; returns the pairs that have a path.
std::vector<std::pair<size_t, size_t>> warm(PathPlanner* planner, const std::vector<Eigen::Vector4d>& goals,
                                            size_t* tried) {
  std::vector<std::pair<size_t, size_t>> pairs;
  *tried = 0;
  for (size_t i = 0; i + 1 < goals.size() && *tried < 150; i += 2, ++*tried) {
    if (hasPath(planner->plan(goals[i], goals[i + 1]).status)) pairs.emplace_back(i, i + 1);
  }
  return pairs;
}

std::vector<Eigen::Vector4d> viewpointGoals(const World& w) {
  std::vector<Eigen::Vector4d> goals;
  for (const Viewpoint& v : w.frontier.viewpoints) goals.emplace_back(v.position.x(), v.position.y(), v.position.z(), v.yaw);
  return goals;
}

void BM_FullRecompute(benchmark::State& state) {
  World& w = world();
  if (!w.ok) return state.SkipWithError("no power plant frontier (is ../shared/scenes/powerplant.dae there?)");
  ExplorerConfig config = w.config.explorer;
  config.path_distances = state.range(0) != 0;
  ExplorerTimings sum;
  size_t n = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Explorer explorer(config, w.config.path);
    explorer.setMap(w.collision.get(), w.config.tsdf.bounds);
    if (config.path_distances) {
      size_t tried = 0;
      warm(&explorer.pathPlanner(), viewpointGoals(w), &tried);
    }
    state.ResumeTiming();
    const ExplorerDecision d = explorer.update(w.frontier, w.uav, false);
    benchmark::DoNotOptimize(d.path.data());
    sum.graph_ms += d.timings.graph_ms, sum.tour_ms += d.timings.tour_ms, sum.path_ms += d.timings.path_ms;
    ++n;
  }
  setCounters(state, sum, n);
}
// Argument: 0 = straight-line cluster-graph distances, 1 = path_distances.
BENCHMARK(BM_FullRecompute)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_LocalUpdate(benchmark::State& state) {
  World& w = world();
  if (!w.ok) return state.SkipWithError("no power plant frontier");
  // The same frontier with its last cluster covered.
  Frontier covered = w.frontier;
  if (!covered.clusters.empty()) {
    for (uint32_t v : covered.clusters.back().viewpoints) covered.viewpoints[v].cluster = -1;
    covered.clusters.pop_back();
  }
  Explorer explorer(w.config.explorer, w.config.path);
  explorer.setMap(w.collision.get(), w.config.tsdf.bounds);
  explorer.update(w.frontier, w.uav, false);
  ExplorerTimings sum;
  size_t n = 0;
  bool flip = false;
  for (auto _ : state) {
    const ExplorerDecision d = explorer.update(flip ? w.frontier : covered, w.uav, false);
    flip = !flip;
    if (d.full_recompute) state.SkipWithError("expected a local update");
    sum.graph_ms += d.timings.graph_ms, sum.tour_ms += d.timings.tour_ms, sum.path_ms += d.timings.path_ms;
    ++n;
  }
  setCounters(state, sum, n);
}
BENCHMARK(BM_LocalUpdate)->Unit(benchmark::kMillisecond)->Iterations(20);

void BM_PathQuery(benchmark::State& state) {
  World& w = world();
  if (!w.ok) return state.SkipWithError("no power plant frontier");
  PathPlannerConfig config = w.config.path;
  config.simplify = state.range(0) != 0;
  config.search = static_cast<QuerySearch>(state.range(1));
  PathPlanner planner(config);
  planner.setMap(w.collision.get(), w.config.tsdf.bounds);
  const std::vector<Eigen::Vector4d> goals = viewpointGoals(w);
  if (goals.size() < 2) return state.SkipWithError("too few viewpoints");
  // Time the pairs that have a path (a pair without one runs to the budget).
  size_t tried = 0;
  const std::vector<std::pair<size_t, size_t>> pairs = warm(&planner, goals, &tried);
  if (pairs.empty()) return state.SkipWithError("no pair of viewpoints is connected");
  std::vector<double> seconds;
  size_t k = 0;
  for (auto _ : state) {
    const auto& [a, b] = pairs[k++ % pairs.size()];
    const PathResult r = planner.plan(goals[a], goals[b]);
    benchmark::DoNotOptimize(r.length);
    seconds.push_back(r.seconds);
  }
  std::nth_element(seconds.begin(), seconds.begin() + seconds.size() / 2, seconds.end());
  state.counters["median_ms"] = 1e3 * seconds[seconds.size() / 2];
  state.counters["connected"] = static_cast<double>(pairs.size()) / tried;
  state.counters["roadmap"] = planner.roadmapVertices();
}
// Arguments: {1 = with the collision-checked shortcutting, 0 = the raw
// roadmap path} x QuerySearch {0 = kFast (our lazy A*), 1 = kOmplSearch
// (LazyPRM::constructSolution), 2 = kOmplSolve (LazyPRM::solve, the old way)}.
BENCHMARK(BM_PathQuery)->ArgsProduct({{1, 0}, {0, 1, 2}})->Unit(benchmark::kMillisecond)->Iterations(200);

void BM_RoadmapEdges(benchmark::State& state) {
  World& w = world();
  if (!w.ok) return state.SkipWithError("no power plant frontier");
  PathPlanner planner(w.config.path);
  planner.setMap(w.collision.get(), w.config.tsdf.bounds);
  const std::vector<Eigen::Vector4d> goals = viewpointGoals(w);
  if (goals.size() < 2) return state.SkipWithError("too few viewpoints");
  for (int64_t q = 0; q < state.range(0); ++q) {
    planner.plan(goals[(2 * q) % goals.size()], goals[(7 * q + 3) % goals.size()]);
  }
  size_t edges = 0;
  for (auto _ : state) {
    const auto e = planner.roadmapEdges(20000);
    edges = e.size();
    benchmark::DoNotOptimize(e.data());
  }
  state.counters["roadmap"] = planner.roadmapVertices();
  state.counters["edges"] = static_cast<double>(edges);
}
BENCHMARK(BM_RoadmapEdges)->Arg(50)->Arg(300)->Unit(benchmark::kMillisecond)->Iterations(20);

void BM_ReachableFill(benchmark::State& state) {
  World& w = world();
  if (!w.ok) return state.SkipWithError("no power plant frontier");
  PathPlanner planner(w.config.path);
  planner.setMap(w.collision.get(), w.config.tsdf.bounds);
  const double radius = planner.clearance() + w.config.explorer.reach_clearance;
  ReachableSpace space;
  for (auto _ : state) {
    space.fill(*w.collision, w.config.tsdf.bounds, w.uav.head<3>(), radius);
    benchmark::DoNotOptimize(space.size());
  }
  const Eigen::Vector3i cells = w.collision->gridCells();
  state.counters["filled"] = static_cast<double>(space.size());
  state.counters["grid"] = static_cast<double>(cells.prod());
}
BENCHMARK(BM_ReachableFill)->Unit(benchmark::kMillisecond)->Iterations(20);

}  // namespace

BENCHMARK_MAIN();
