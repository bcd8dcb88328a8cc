// Tracking cost:
//   - MpcSolve/N: one MPC step (position and yaw QPs, warm-started) for
//     horizons N = 10, 20, 40 while following a 2 m circle at 0.5 m/s; the
//     counter `iters` is the mean ADMM iterations per step (position + yaw).
//   - TrackerSimRealTime: the simulated UAV alone (sim_dt 0.01 s, MPC every
//     0.1 s, N = 20) flying the circle; `sim_s_per_s` is the real-time factor.
#include <benchmark/benchmark.h>

#include <cmath>

#include "surface_nbv/tracking/tracker_sim.h"

using namespace surface_nbv;

namespace {

Trajectory circle(double laps) {
  std::vector<Waypoint> w;
  const int n = static_cast<int>(72 * laps);
  for (int i = 0; i <= n; ++i) {
    const double a = i * M_PI / 36;
    w.push_back({Eigen::Vector3d(2 * std::cos(a), 2 * std::sin(a), 3), wrapAngle(a + M_PI)});
  }
  return timeWaypoints(w, 0.0, 0.5, 1.0);
}

UavState circleStart() {
  UavState s;
  s.p_W = Eigen::Vector3d(2, 0, 3);
  s.yaw = M_PI;
  return s;
}

void MpcSolve(benchmark::State& bench) {
  MpcConfig config;
  config.horizon = static_cast<int>(bench.range(0));
  const UavModelConfig model_config;
  MpcTracker mpc(config, model_config);
  UavModel model(model_config, circleStart());
  const Trajectory traj = circle(100);
  double t = 0.0;
  int64_t iterations = 0;
  UavCommand command;
  for (auto _ : bench) {
    MpcReference ref;
    ref.p_W.resize(3, config.horizon);
    ref.v_W.resize(3, config.horizon);
    ref.yaw.resize(config.horizon);
    for (int k = 0; k < config.horizon; ++k) {
      const TrajectorySample s = traj.sample(t + (k + 1) * config.dt);
      ref.p_W.col(k) = s.p_W;
      ref.v_W.col(k) = s.v_W;
      ref.yaw[k] = s.yaw;
    }
    const MpcResult r = mpc.solve(model.state(), ref, command);
    benchmark::DoNotOptimize(r.command.a_W.data());
    iterations += r.iterations;
    command = model.step(r.command, config.dt);
    t += config.dt;
  }
  bench.counters["iters"] = benchmark::Counter(static_cast<double>(iterations) / bench.iterations());
}
BENCHMARK(MpcSolve)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);

void TrackerSimRealTime(benchmark::State& bench) {
  const Trajectory traj = circle(1);
  double simulated = 0.0;
  for (auto _ : bench) {
    TrackerSim sim(TrackerSimConfig(), circleStart());
    sim.setTrajectory(traj);
    sim.runUntil(traj.endTime());
    simulated += sim.time();
    benchmark::DoNotOptimize(sim.state().p_W.data());
  }
  bench.counters["sim_s_per_s"] = benchmark::Counter(simulated, benchmark::Counter::kIsRate);
}
BENCHMARK(TrackerSimRealTime)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
