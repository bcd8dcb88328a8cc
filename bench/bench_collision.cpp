// Collision map cost on maps the size of the paper's scenes, in a realistic
// half-known state (one half observed: free space, a 3-voxel occupied shell on
// every solid, unknown inside solids; the other half never seen):
//   - building from scratch (power plant 72 x 50 x 17 m at 0.3 m; statue
//     28 x 28 x 64 m at 0.15 m with 0.3 m and 0.15 m collision cells),
//   - distance() per query, uniform over the bounds and in known free space,
//   - update() after 20 blocks at the frontier change (unknown <-> observed).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "surface_nbv/map/collision_map.h"

using namespace surface_nbv;

namespace {

struct Scenario {
  std::string name;
  TsdfConfig config;
  std::vector<AlignedBox> solids;
  double known_below_x;  // the observed half
};

Scenario powerplant() {
  Scenario s;
  s.name = "powerplant";
  s.config.voxel_size = 0.3;
  s.config.bounds = AlignedBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(72, 50, 17));
  s.solids = {AlignedBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(72, 50, 0.6)),      // ground
              AlignedBox(Eigen::Vector3d(8, 10, 0), Eigen::Vector3d(40, 30, 12)),      // hall
              AlignedBox(Eigen::Vector3d(44, 8, 0), Eigen::Vector3d(60, 20, 9)),       // annex
              AlignedBox(Eigen::Vector3d(20, 34, 0), Eigen::Vector3d(21, 44, 10)),     // wall
              AlignedBox(Eigen::Vector3d(10, 36, 8), Eigen::Vector3d(40, 37, 8.6))};   // gantry
  for (int i = 0; i < 5; ++i) {  // flues
    const double x = 12 + 10 * i;
    s.solids.push_back(AlignedBox(Eigen::Vector3d(x, 40, 0), Eigen::Vector3d(x + 3, 43, 15)));
  }
  s.known_below_x = 36;
  return s;
}

Scenario statue() {
  Scenario s;
  s.name = "statue";
  s.config.voxel_size = 0.15;
  s.config.bounds = AlignedBox(Eigen::Vector3d(-14, -14, 0), Eigen::Vector3d(14, 14, 64));
  s.solids = {AlignedBox(Eigen::Vector3d(-14, -14, 0), Eigen::Vector3d(14, 14, 0.45)),
              AlignedBox(Eigen::Vector3d(-10, -10, 0), Eigen::Vector3d(10, 10, 14)),  // pedestal
              AlignedBox(Eigen::Vector3d(-4, -4, 14), Eigen::Vector3d(4, 4, 52)),     // body
              AlignedBox(Eigen::Vector3d(2, -1, 52), Eigen::Vector3d(3, 1, 60))};     // arm and torch
  s.known_below_x = 0;
  return s;
}

// Depth of p inside the solids (0 outside).
double depthInside(const std::vector<AlignedBox>& solids, const Eigen::Vector3d& p) {
  double depth = 0.0;
  for (const AlignedBox& b : solids) {
    if (!b.contains(p)) continue;
    depth = std::max(depth, std::min((p - b.min).minCoeff(), (b.max - p).minCoeff()));
  }
  return depth;
}

void observe(const Scenario& s, TsdfMap* map, const Eigen::Vector3i& block) {
  TsdfBlock* b = map->allocateBlock(block);
  if (b == nullptr) return;
  const double shell = 3 * map->voxelSize();
  for (int z = 0; z < kBlockSize; ++z)
    for (int y = 0; y < kBlockSize; ++y)
      for (int x = 0; x < kBlockSize; ++x) {
        const Eigen::Vector3i v = block * kBlockSize + Eigen::Vector3i(x, y, z);
        const double depth = depthInside(s.solids, map->voxelCenter(v));
        TsdfVoxel& voxel = b->at(x, y, z);
        voxel.w = depth > shell ? 0.0f : 1.0f;
        voxel.phi = depth > 0.0 ? static_cast<float>(-depth) : 0.5f;
      }
  b->change_stamp = map->beginChange();
}

void forget(TsdfMap* map, const Eigen::Vector3i& block) {
  TsdfBlock* b = map->mutableBlock(block);
  if (b == nullptr) return;
  for (TsdfVoxel& v : b->voxels) v = TsdfVoxel();
  b->change_stamp = map->beginChange();
}

std::unique_ptr<TsdfMap> halfKnownMap(const Scenario& s) {
  auto map = std::make_unique<TsdfMap>(s.config);
  const Eigen::Vector3i& g = map->gridBlocks();
  const double block_m = kBlockSize * s.config.voxel_size;
  for (int z = 0; z < g.z(); ++z)
    for (int y = 0; y < g.y(); ++y)
      for (int x = 0; x < g.x(); ++x) {
        if (s.config.bounds.min.x() + (x + 1) * block_m <= s.known_below_x) observe(s, map.get(), Eigen::Vector3i(x, y, z));
      }
  return map;
}

const TsdfMap* cachedMap(const Scenario& s, bool half_known) {
  static std::map<std::string, std::unique_ptr<TsdfMap>> cache;
  const std::string key = s.name + (half_known ? "/half" : "/unknown");
  auto& slot = cache[key];
  if (!slot) slot = half_known ? halfKnownMap(s) : std::make_unique<TsdfMap>(s.config);
  return slot.get();
}

CollisionConfig collisionConfig(double min_cell_size) {
  CollisionConfig c;
  c.min_cell_size = min_cell_size;
  return c;
}

// range(0): 0 power plant, 1 statue. range(1): 1 half known, 0 all unknown.
// range(2): min_cell_size in cm.
void BM_Build(benchmark::State& state) {
  const Scenario s = state.range(0) == 0 ? powerplant() : statue();
  const TsdfMap* map = cachedMap(s, state.range(1) == 1);
  const CollisionConfig config = collisionConfig(state.range(2) / 100.0);
  size_t bytes = 0, cells = 0;
  for (auto _ : state) {
    CollisionMap coll(*map, config);
    bytes = coll.memoryBytes();
    cells = static_cast<size_t>(coll.gridCells().prod());
    benchmark::DoNotOptimize(coll.distance(s.config.bounds.center()));
  }
  state.SetLabel(s.name + (state.range(1) == 1 ? " half known" : " unknown"));
  state.counters["Mcells"] = cells / 1e6;
  state.counters["MB"] = bytes / 1e6;
}
BENCHMARK(BM_Build)
    ->Args({0, 0, 30})
    ->Args({0, 1, 30})
    ->Args({1, 0, 30})
    ->Args({1, 1, 30})
    ->Args({1, 0, 15})
    ->Args({1, 1, 15})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

struct QueryFixture {
  std::unique_ptr<CollisionMap> coll;
  std::vector<Eigen::Vector3d> uniform, free_space, edges;
};

QueryFixture makeQueryFixture() {
  QueryFixture f;
  const Scenario s = powerplant();
  const TsdfMap* map = cachedMap(s, true);
  f.coll = std::make_unique<CollisionMap>(*map, collisionConfig(0.3));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  while (f.free_space.size() < (1u << 16)) {
    const Eigen::Vector3d p =
        s.config.bounds.min + Eigen::Vector3d(u(rng), u(rng), u(rng)).cwiseProduct(s.config.bounds.size());
    if (f.uniform.size() < (1u << 16)) f.uniform.push_back(p);
    Eigen::Vector3i v;
    if (map->voxelIndex(p, &v) && map->state(v) == VoxelState::kFree) f.free_space.push_back(p);
  }
  // Motion checks as OMPL makes them: 5 m edges from free space, every 0.1 m.
  for (size_t i = 0; f.edges.size() < (1u << 16); ++i) {
    const Eigen::Vector3d dir = Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, 0.5 * (u(rng) - 0.5)).normalized();
    for (int k = 0; k < 50; ++k) f.edges.push_back(f.free_space[i] + 0.1 * k * dir);
  }
  f.edges.resize(1u << 16);
  size_t is_free = 0;
  for (const Eigen::Vector3d& p : f.free_space) is_free += f.coll->isFree(p, 1.0) ? 1 : 0;
  std::printf("powerplant half known: %zu blocks, %.1f MB collision map, %.0f%% of free-space samples clear at 1 m\n",
              map->numBlocks(), f.coll->memoryBytes() / 1e6, 100.0 * is_free / f.free_space.size());
  return f;
}

const QueryFixture& queryFixture() {
  static const QueryFixture f = makeQueryFixture();  // thread-safe initialisation
  return f;
}

// range(0): 0 uniform over the bounds, 1 in known free space, 2 along edges.
void BM_Distance(benchmark::State& state) {
  const QueryFixture& f = queryFixture();
  const std::vector<Eigen::Vector3d>& points =
      state.range(0) == 0 ? f.uniform : (state.range(0) == 1 ? f.free_space : f.edges);
  size_t i = static_cast<size_t>(state.thread_index()) * 977;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.coll->distance(points[i++ & (points.size() - 1)]));
  }
  state.SetLabel(state.range(0) == 0 ? "uniform" : (state.range(0) == 1 ? "free space" : "along edges"));
}
BENCHMARK(BM_Distance)->DenseRange(0, 2)->Threads(1)->Threads(2);

// 20 blocks just past the observed half, alternately observed and forgotten.
void BM_Update20Blocks(benchmark::State& state) {
  const Scenario s = powerplant();
  auto map = halfKnownMap(s);
  CollisionMap coll(*map, collisionConfig(0.3));
  const int bx = static_cast<int>(s.known_below_x / (kBlockSize * s.config.voxel_size));
  std::vector<Eigen::Vector3i> blocks;
  for (int z = 0; z < 4; ++z)
    for (int y = 13; y < 18; ++y) blocks.emplace_back(bx, y, z);
  bool observed = false;
  size_t changed = 0, updates = 0;
  for (auto _ : state) {
    state.PauseTiming();
    for (const Eigen::Vector3i& b : blocks) observed ? forget(map.get(), b) : observe(s, map.get(), b);
    observed = !observed;
    state.ResumeTiming();
    coll.update(*map);
    changed += coll.lastCellsChanged();
    ++updates;
  }
  state.counters["blocks"] = static_cast<double>(coll.lastBlocksVisited());
  state.counters["cells_changed"] = static_cast<double>(changed) / std::max<size_t>(updates, 1);
}
BENCHMARK(BM_Update20Blocks)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
