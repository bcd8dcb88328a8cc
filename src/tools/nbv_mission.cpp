// nbv_mission: the headless mission runner. Runs N seeded exploration trials
// of a scene with the same core objects and the same YAML parameters as the
// ROS launch (no ROS master), evaluates every reconstruction against the
// scene's ground truth and writes the paper's Table 2 columns.
//
//   nbv_mission --scene plant|statue|FILE [--config YAML] [--trials N] [--seed S]
//               [--out DIR] [--threads N] [--max-flight-time S] [--max-path-length M]
//               [--voxel-size M] [--coverage-every S] [--no-plots]
//
// Keys no config gives (bounds, take-off pose, camera range, voxel size,
// Table 1) are derived from the scene (scene_defaults.h): printed first and
// written to report.json ("derived").
// Per trial (DIR/trial_K/): reconstruction.ply, map.tsdf, path.csv (flown
// poses), events.csv (every frontier update), eval/ (nbv_evaluate's report and
// clouds) and PNG plots; in DIR: report.json and report.md over all trials.
// --coverage-every S also meshes and evaluates the reconstruction every S
// seconds of flight and at the end (trial_K/coverage.csv, the reports and
// progress.png): the coverage over time, with the same evaluation as the
// trial's own (the flights are the same with or without).
// The trials themselves are TrialRunner's (mission/trial_runner.h); this is
// its command line.
#include <iostream>
#include <optional>
#include <type_traits>
#include <vector>

#include "surface_nbv/mission/trial_runner.h"
#include "surface_nbv/sim/scene_source.h"
#include "surface_nbv/util/cli_args.h"

using namespace surface_nbv;

namespace {

const char* kUsage =
    "usage: nbv_mission --scene plant|statue|FILE [--config YAML] [--trials N] [--seed S] [--out DIR]\n"
    "                   [--threads N] [--max-flight-time S] [--max-path-length M] [--up-axis z|y]\n"
    "                   [--scale S] [--fit-size X,Y,Z] [--offset X,Y,Z] [--crop-min X,Y,Z] [--crop-max X,Y,Z]\n"
    "                   [--voxel-size M] [--coverage-every S] [--oracle-gain N]\n"
    "                   [--oracle-lambda L] [--no-plots]\n"
    "  --config defaults to config/<scene name>.yaml of the package when it exists; the keys no config gives\n"
    "    (bounds, take-off pose, camera range, voxel size, Table 1) are derived from the scene.\n"
    "  --voxel-size M sets nbv/voxel_size over the config's.\n"
    "  --coverage-every S evaluates the reconstruction every S seconds of flight (coverage over time).\n"
    "  --oracle-gain N (a diagnostic) flies the best of the tour's first N viewpoints first, ranked by the\n"
    "    true surface not yet observed in their view (the scene's mesh) times exp(-L d), L = lambda_tc\n"
    "    unless --oracle-lambda L.\n";

int fail(const std::string& message) {
  std::cerr << "nbv_mission: " << message << "\n";
  return 2;
}

// The value of --key when given.
template <typename T>
Status getOptional(const CliArgs& args, const std::string& key, std::optional<T>* value) {
  if (!args.has(key)) return Status::Ok();
  T v{};
  Status s;
  if constexpr (std::is_same_v<T, int>) {
    s = args.getInt(key, &v);
  } else if constexpr (std::is_same_v<T, double>) {
    s = args.getDouble(key, &v);
  } else if constexpr (std::is_same_v<T, std::string>) {
    v = args.get(key, "");
  } else {
    std::vector<double> xyz;
    s = args.getDoubles(key, 3, &xyz);
    if (s) v = Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
  }
  if (s) *value = v;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> names = sceneOptionNames();
  names.insert(names.end(), {"config", "trials", "seed", "out", "threads", "max-flight-time", "max-path-length",
                             "coverage-every", "oracle-gain", "oracle-lambda", "voxel-size"});
  CliArgs args(names, {"help", "no-plots"});
  bool help = false;
  if (Status s = args.parseCommand(argc, argv, kUsage, std::cout, &help); !s) return fail(s.message());
  if (help) return 0;
  TrialOptions o;
  o.package_dir = NBV_SOURCE_DIR;
  std::optional<int> trials, seed;
  const Status parsed[] = {getOptional(args, "config", &o.config_file), getOptional(args, "scene", &o.scene),
                           getOptional(args, "up-axis", &o.up_axis), getOptional(args, "scale", &o.scale),
                           getOptional(args, "fit-size", &o.fit_size), getOptional(args, "offset", &o.offset),
                           getOptional(args, "crop-min", &o.crop_min), getOptional(args, "crop-max", &o.crop_max),
                           getOptional(args, "trials", &trials), getOptional(args, "seed", &seed),
                           getOptional(args, "oracle-gain", &o.oracle_gain),
                           getOptional(args, "oracle-lambda", &o.oracle_lambda),
                           getOptional(args, "coverage-every", &o.coverage_every), getOptional(args, "threads", &o.threads),
                           getOptional(args, "max-flight-time", &o.max_flight_time),
                           getOptional(args, "max-path-length", &o.max_path_length),
                           getOptional(args, "voxel-size", &o.voxel_size), getOptional(args, "out", &o.out_dir)};
  for (const Status& s : parsed)
    if (!s) return fail(s.message());
  o.trials = trials.value_or(o.trials);
  o.seed = seed.value_or(o.seed);
  o.plots = !args.has("no-plots");
  TrialResult result;
  if (Status s = TrialRunner(std::cout, std::cerr).run(o, &result); !s) return fail(s.message());
  return result.allCompleted() ? 0 : 1;
}
