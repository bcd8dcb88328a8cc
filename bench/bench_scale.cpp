// How planning scales with the frontier's size, on the built-in multistorey
// scene (config/multistorey.yaml, 46,901 m^2). One headless mission (seed 1)
// is flown until its frontier first holds 1k, 5k and 10k ISEs (or until
// --max-flight-time); the planning map at each of those updates is saved to
// build/bench_scale/ (reused by later runs unless --fresh). On each saved map,
// --repetitions times, one thread:
//   frontier   the whole frontier rebuild by stage (ISEs from scratch, poses,
//              merge, visibility, clusters), then
//              a second update with the map unchanged (the part of an update
//              that does not depend on how much of the map changed; every
//              ISE keeps its pose search, frontier_builder.h)
//   full       Explorer full recomputation: cluster graph, LK tour, first leg
//   local      Explorer local update: one cluster covered, the tour kept
// Medians (ms) go to stdout as a Markdown table, with the mission's peak RSS.
//   scripts/bench scale [--fresh] [--repetitions N] [--max-flight-time S]
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bench_scenes.h"
#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/map/map_io.h"
#include "surface_nbv/mission/mission_runner.h"
#include "surface_nbv/planning/explorer.h"
#include "surface_nbv/surface/frontier_builder.h"
#include "surface_nbv/util/cli_args.h"

using namespace surface_nbv;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

double peakRssMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // KiB on Linux
}

struct Snapshot {
  size_t target = 0;
  std::string path;
  Eigen::Vector4d uav = Eigen::Vector4d::Zero();
  double t = 0.0;
};

// Saved as map_<target>.tsdf with the UAV pose and time in a side file.
bool readSnapshot(Snapshot* s) {
  FILE* f = std::fopen((s->path + ".pose").c_str(), "r");
  if (f == nullptr || !fs::exists(s->path)) {
    if (f) std::fclose(f);
    return false;
  }
  const int n = std::fscanf(f, "%lf %lf %lf %lf %lf", &s->uav[0], &s->uav[1], &s->uav[2], &s->uav[3], &s->t);
  std::fclose(f);
  return n == 5;
}

struct Row {
  size_t ises = 0, viewpoints = 0, clusters = 0, tour = 0;
  double t = 0.0;
  std::vector<double> ise, poses, merge, visibility, clusters_ms, frontier, unchanged, unchanged_poses;
  std::vector<double> graph, tsp, leg, full, local;
};

}  // namespace

int main(int argc, char** argv) {
  CliArgs args({"repetitions", "max-flight-time"}, {"fresh", "help"});
  if (Status s = args.parse(argc, argv); !s) {
    std::fprintf(stderr, "bench_scale: %s\n", s.message().c_str());
    return 2;
  }
  if (args.has("help")) {
    std::printf("usage: bench_scale [--fresh] [--repetitions N] [--max-flight-time S]\n");
    return 0;
  }
  int repetitions = 5;
  double max_flight = 5400.0;
  if (Status s = args.getInt("repetitions", &repetitions); !s || repetitions < 1) {
    std::fprintf(stderr, "bench_scale: --repetitions expected an integer >= 1\n");
    return 2;
  }
  if (Status s = args.getDouble("max-flight-time", &max_flight); !s || !(max_flight > 0.0)) {
    std::fprintf(stderr, "bench_scale: --max-flight-time expected > 0 s\n");
    return 2;
  }
  MissionConfig config;
  if (Status s = loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/multistorey.yaml", &config); !s) {
    std::fprintf(stderr, "bench_scale: %s\n", s.message().c_str());
    return 1;
  }
  config.scene = benchSceneConfig("multistorey");
  config.seed = 1;
  config.max_flight_time = max_flight;
  config.progress_period = 1e-3;  // every frontier update
  TriangleMesh mesh;
  std::unique_ptr<RaycastScene> scene;
  if (Status s = loadScene(config.scene, &mesh); !s || !RaycastScene::create(mesh, &scene)) {
    std::fprintf(stderr, "bench_scale: cannot build the multistorey scene\n");
    return 1;
  }
  const std::string dir = std::string(NBV_BUILD_DIR) + "/bench_scale";
  fs::create_directories(dir);
  std::vector<Snapshot> snaps;
  for (size_t target : {1000, 5000, 10000}) snaps.push_back({target, dir + "/map_" + std::to_string(target) + ".tsdf"});
  const bool cached = !args.has("fresh") && std::all_of(snaps.begin(), snaps.end(), [](Snapshot& s) { return readSnapshot(&s); });
  double mission_rss = 0.0;
  if (!cached) {
    std::fprintf(stderr, "bench_scale: flying multistorey (seed 1) until 10k ISEs or %.0f s of flight...\n", max_flight);
    MissionRunner runner(config, *scene);
    size_t next = 0;
    runner.setProgress([&](const MissionEvent& e) {
      if (next >= snaps.size() || e.ises < snaps[next].target) return;
      Snapshot& s = snaps[next++];
      s.uav = e.uav, s.t = e.t;
      if (Status st = saveMap(runner.map(), s.path); !st) std::fprintf(stderr, "bench_scale: %s\n", st.message().c_str());
      if (FILE* f = std::fopen((s.path + ".pose").c_str(), "w")) {
        std::fprintf(f, "%.9g %.9g %.9g %.9g %.9g\n", s.uav[0], s.uav[1], s.uav[2], s.uav[3], s.t);
        std::fclose(f);
      }
      std::fprintf(stderr, "bench_scale: %zu ISEs at %.0f s of flight (%.0f m) -> %s\n", e.ises, e.t, e.path_length,
                   s.path.c_str());
    });
    const MissionResult r = runner.run();
    if (!r.status) {
      std::fprintf(stderr, "bench_scale: mission failed: %s\n", r.status.message().c_str());
      return 1;
    }
    mission_rss = peakRssMiB();
    std::fprintf(stderr, "bench_scale: mission stopped at %.0f s of flight, %.1f s wall (%s), peak RSS %.0f MiB\n",
                 r.flight_time, r.wall_time, r.end_reason.c_str(), mission_rss);
    snaps.erase(std::remove_if(snaps.begin(), snaps.end(), [](Snapshot& s) { return !readSnapshot(&s); }), snaps.end());
  }

  std::vector<Row> rows;
  for (const Snapshot& snap : snaps) {
    TsdfConfig tsdf = config.tsdf;
    tsdf.threads = 1;
    TsdfMap map(tsdf);
    if (Status s = loadMap(snap.path, &map); !s) {
      std::fprintf(stderr, "bench_scale: %s\n", s.message().c_str());
      continue;
    }
    CollisionMap collision(map, config.collision);
    SurfaceConfig surface = config.surface;
    surface.threads = 1;
    Row row;
    row.t = snap.t;
    Frontier frontier;
    for (int k = 0; k < repetitions; ++k) {
      FrontierBuilder builder(surface);  // fresh: extracts from scratch
      if (!builder.update(map, collision, &frontier)) break;
      const FrontierStats& st = frontier.stats;
      row.ise.push_back(st.ise_ms), row.poses.push_back(st.viewpoints_ms), row.merge.push_back(st.merge_ms);
      row.visibility.push_back(st.visibility_ms), row.clusters_ms.push_back(st.clusters_ms);
      row.frontier.push_back(st.total_ms);
      // The next update with no map change: what is left of a rebuild when
      // the ISE extraction has nothing to redo.
      Frontier again;
      builder.update(map, collision, &again);
      row.unchanged.push_back(again.stats.total_ms);
      row.unchanged_poses.push_back(again.stats.viewpoints_ms);  // every pose search kept
    }
    row.ises = frontier.ises.size(), row.viewpoints = frontier.viewpoints.size(), row.clusters = frontier.clusters.size();
    Frontier covered = frontier;
    if (!covered.clusters.empty()) {
      for (uint32_t v : covered.clusters.back().viewpoints) covered.viewpoints[v].cluster = -1;
      covered.clusters.pop_back();
    }
    for (int k = 0; k < repetitions; ++k) {
      PathPlannerConfig path = config.path;
      path.seed = config.seed;
      Explorer explorer(config.explorer, path);
      explorer.setMap(&collision, tsdf.bounds);
      const auto t0 = Clock::now();
      const ExplorerDecision d = explorer.update(frontier, snap.uav, false);
      row.full.push_back(msSince(t0));
      row.graph.push_back(d.timings.graph_ms), row.tsp.push_back(d.timings.tour_ms), row.leg.push_back(d.timings.path_ms);
      row.tour = explorer.tour().size();
      const auto t1 = Clock::now();
      const ExplorerDecision l = explorer.update(covered, snap.uav, false);
      row.local.push_back(msSince(t1));
      if (l.full_recompute) std::fprintf(stderr, "bench_scale: the covered frontier gave a full recompute\n");
    }
    rows.push_back(std::move(row));
  }
  std::printf("\n| ISEs | viewpoints | clusters | tour | flight s | ISE extraction | poses | merge | visibility | clusters | "
              "frontier total | frontier, map unchanged | of which poses | graph | tour (LK) | leg | full recompute | "
              "local update |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    std::printf("| %zu | %zu | %zu | %zu | %.0f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |\n",
                r.ises, r.viewpoints, r.clusters, r.tour, r.t, median(r.ise), median(r.poses), median(r.merge),
                median(r.visibility), median(r.clusters_ms), median(r.frontier), median(r.unchanged),
                median(r.unchanged_poses), median(r.graph),
                median(r.tsp), median(r.leg), median(r.full), median(r.local));
  }
  std::printf("\nmedians of %d repetitions, ms, one thread; peak RSS %.0f MiB%s\n", repetitions, peakRssMiB(),
              cached ? " (maps from build/bench_scale, --fresh flies the mission again)" : "");
  return rows.empty() ? 1 : 0;
}
