// nbv_evaluate: compares a reconstructed mesh with the ground truth
// (docs/method.md, "Evaluation protocol"): surface coverage within
// e_max = rho_v sqrt(3) / 2 of the ground truth a sensor can see, and the
// M3C2-like signed error along the ground-truth normal. Writes report.json,
// report.md and PLY clouds to --out; --plots adds PNG plots (python3-matplotlib).
//
//   nbv_evaluate --reconstruction output/flight_plant/reconstruction.ply --ground-truth plant --voxel-size 0.3
//   nbv_evaluate --reconstruction rec.ply --ground-truth ../shared/scenes/powerplant.dae --scale 0.656
//                --crop-max 1e9,1e9,15 --voxel-size 0.3 --plots
//
// Exit codes: 0 done, 2 bad arguments, 1 a failure (file, evaluation, report).

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <iostream>

#include "surface_nbv/mission/mission_config.h"
#include "surface_nbv/eval/evaluator.h"
#include "surface_nbv/eval/report_writer.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/sim/scene_source.h"
#include "surface_nbv/util/run_process.h"

using namespace surface_nbv;

namespace {

constexpr char kUsage[] =
    "usage: nbv_evaluate --reconstruction MESH --ground-truth MESH|SCENE --voxel-size M\n"
    "                    [--up-axis z|y] [--scale S] [--fit-size X,Y,Z] [--offset X,Y,Z]  (ground truth)\n"
    "                    [--crop-min X,Y,Z] [--crop-max X,Y,Z]  (ground truth)\n"
    "                    [--bounds X0,Y0,Z0,X1,Y1,Z1] [--spacing M] [--min-range M] [--max-range M]\n"
    "                    [--collision-radius M] [--no-pruning] [--seed N] [--threads N (2)] [--out DIR] [--plots]\n"
    "Samples every --spacing (default voxel size / 3); coverage within e_max = voxel size * sqrt(3) / 2.\n";

int badArguments(const std::string& message) {
  std::cerr << "nbv_evaluate: " << message << "\n" << kUsage;
  return 2;
}

int failure(const std::string& message) {
  std::cerr << "nbv_evaluate: " << message << "\n";
  return 1;
}

Status configFromArgs(const CliArgs& args, EvalConfig* config) {
  if (!args.has("voxel-size") && !args.has("config")) return Status::Error("--voxel-size (or --config) is required");
  int seed = static_cast<int>(config->seed);
  const Status parsed[] = {args.getDouble("voxel-size", &config->voxel_size),
                           args.getDouble("spacing", &config->point_spacing),
                           args.getDouble("min-range", &config->min_range),
                           args.getDouble("max-range", &config->max_range),
                           args.getDouble("collision-radius", &config->collision_radius),
                           args.getInt("threads", &config->threads),
                           args.getInt("seed", &seed)};
  for (const Status& s : parsed) {
    if (!s) return s;
  }
  if (seed < 0) return Status::Error("--seed expects a non-negative integer");
  config->seed = static_cast<uint64_t>(seed);
  config->prune_hidden = !args.has("no-pruning");
  std::vector<double> b;
  if (Status s = args.getDoubles("bounds", 6, &b); !s) return s;
  if (!b.empty()) config->bounds = AlignedBox(Eigen::Vector3d(b[0], b[1], b[2]), Eigen::Vector3d(b[3], b[4], b[5]));
  return config->validate();
}

// Runs scripts/plot_evaluation.py on the report directory when python3 and
// matplotlib are there; says what it did either way.
int makePlots(const std::string& out_dir) {
  const std::string python = "/usr/bin/python3";
  const std::string script = std::string(NBV_SOURCE_DIR) + "/scripts/plot_evaluation.py";
  if (!std::filesystem::exists(script)) {
    std::printf("plots skipped: %s not found\n", script.c_str());
    return 0;
  }
  if (runProcess({python, "-c", "import matplotlib"}, true) != 0) {
    std::printf("plots skipped: python3-matplotlib is not installed (apt-get install python3-matplotlib)\n");
    return 0;
  }
  std::fflush(stdout);
  if (runProcess({python, script, out_dir}, false) != 0)
    return failure("plotting failed: " + python + " " + script + " " + out_dir);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> options = {"reconstruction", "ground-truth", "voxel-size", "bounds", "config",
                                      "spacing",        "min-range",    "max-range",  "collision-radius",
                                      "seed",           "threads",      "out"};
  for (const std::string& name : sceneOptionNames()) {
    if (name != "scene") options.push_back(name);
  }
  CliArgs args(options, {"no-pruning", "plots", "help"});
  bool help = false;
  if (Status s = args.parseCommand(argc, argv, kUsage, std::cout, &help); !s) return badArguments(s.message());
  if (help) return 0;
  if (!args.has("reconstruction") || !args.has("ground-truth")) {
    return badArguments("--reconstruction and --ground-truth are required");
  }
  EvalConfig config;
  SceneConfig ground_truth_config;
  if (args.has("config")) {  // as nbv_mission evaluates (missionEvalConfig)
    MissionConfig mission;
    std::stringstream files(args.get("config", ""));
    for (std::string file; std::getline(files, file, ',');) {
      if (Status s = loadMissionConfig(file, &mission); !s) return failure(s.message());
    }
    config = missionEvalConfig(mission);
    ground_truth_config.transform = mission.scene.transform;
  }
  config.threads = 2;
  if (Status s = configFromArgs(args, &config); !s) return badArguments(s.message());
  ground_truth_config.scene = args.get("ground-truth", "");
  if (Status s = sceneConfigFromArgs(args, &ground_truth_config); !s) return badArguments(s.message());
  const std::string reconstruction_path = args.get("reconstruction", "");
  const std::string out_dir =
      args.get("out", "output/eval_" + std::filesystem::path(reconstruction_path).parent_path().filename().string() +
                          "_" + std::filesystem::path(reconstruction_path).stem().string());

  TriangleMesh ground_truth, reconstruction;
  if (Status s = loadScene(ground_truth_config, &ground_truth); !s) return failure(s.message());
  if (Status s = loadMesh(reconstruction_path, MeshLoadOptions(), &reconstruction); !s) return failure(s.message());
  std::printf("ground truth '%s': %zu triangles, %.1f m^2; reconstruction '%s': %zu triangles, %.1f m^2\n",
              ground_truth_config.scene.c_str(), ground_truth.numTriangles(), ground_truth.area(),
              reconstruction_path.c_str(), reconstruction.numTriangles(), reconstruction.area());
  EvalResult result;
  if (Status s = Evaluator(config).evaluate(ground_truth, reconstruction, &result); !s) return failure(s.message());
  const ErrorStats& e = result.error_stats;
  std::printf("samples every %.3f m: %zu ground truth (%zu visible, %zu hidden), %zu reconstruction\n",
              config.spacing(), result.ground_truth.size(), result.numVisible(), result.numHidden(),
              result.reconstruction.size());
  std::printf(
      "coverage %.2f %% within e_max = %.2f cm; M3C2 error over %zu samples: mean %.2f cm, std %.2f cm, "
      "RMSE %.2f cm\n",
      100.0 * result.coverage.coverage(), 100.0 * config.eMax(), result.matched, 100.0 * e.mean, 100.0 * e.std_dev,
      100.0 * e.rmse);
  std::printf("time %.2f s (%d threads)\n", result.timings.total_s, config.threads);
  EvalInputs inputs{reconstruction_path, ground_truth_config.scene};
  if (Status s = ReportWriter(result, inputs).write(out_dir); !s) return failure(s.message());
  std::printf(
      "wrote %s/report.json, report.md, ground_truth_visible.ply, ground_truth_hidden.ply, coverage.ply, "
      "error.ply\n",
      out_dir.c_str());
  return args.has("plots") ? makePlots(out_dir) : 0;
}
