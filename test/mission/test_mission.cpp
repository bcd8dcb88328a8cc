// The headless mission: its YAML reader and a whole mission on the box scene.
#include "surface_nbv/mission/mission_runner.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "surface_nbv/eval/evaluator.h"
#include "surface_nbv/eval/surface_sampler.h"
#include "surface_nbv/map/mesh_extractor.h"
#include "surface_nbv/sim/procedural_scenes.h"

using namespace surface_nbv;

namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// A column of the paper's Table 1.
struct Table1 {
  double voxel_size, min_range, max_range, delta_pose, d_nu, lambda_tc, lambda_ic;
};
const Table1 kPowerplant{0.3, 1.6, 8.0, 4.7, 2.0, 0.3, 0.03};
const Table1 kStatue{0.15, 1.0, 5.0, 3.6, 2.5, 0.17, 0.15};

void expectTable1(const MissionConfig& c, const Table1& t) {
  EXPECT_DOUBLE_EQ(c.tsdf.voxel_size, t.voxel_size);
  EXPECT_DOUBLE_EQ(c.camera.min_range, t.min_range);
  EXPECT_DOUBLE_EQ(c.camera.max_range, t.max_range);
  EXPECT_DOUBLE_EQ(c.surface.camera.max_range, t.max_range);
  EXPECT_DOUBLE_EQ(c.surface.delta_pose, t.delta_pose);
  EXPECT_DOUBLE_EQ(c.surface.d_nu, t.d_nu);
  EXPECT_DOUBLE_EQ(c.explorer.graph.lambda_tc, t.lambda_tc);
  EXPECT_DOUBLE_EQ(c.explorer.graph.lambda_ic, t.lambda_ic);
}

// config/box.yaml and its scene; legs bounded by roadmap samples, not wall
// time, so that a repeated mission flies the same flight.
struct BoxMission {
  MissionConfig config;
  TriangleMesh mesh;
  std::unique_ptr<RaycastScene> scene;
};

void loadBoxMission(BoxMission* box) {
  ASSERT_TRUE(loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/box.yaml", &box->config).ok());
  box->config.progress_period = 30.0;
  box->config.path.iteration_budget = 20000;
  box->config.path.time_budget = 60.0;
  ASSERT_TRUE(loadScene(box->config.scene, &box->mesh).ok());
  ASSERT_TRUE(RaycastScene::create(box->mesh, &box->scene).ok());
}

EvalConfig boxEvalConfig(const MissionConfig& c) {
  EvalConfig eval;
  eval.voxel_size = c.tsdf.voxel_size;
  eval.min_range = c.camera.min_range;
  eval.max_range = c.camera.max_range;
  eval.threads = 2;
  return eval;
}

TEST(MissionConfig, ReadsTheSharedPlantParameters) {
  MissionConfig c;
  ASSERT_TRUE(loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/plant.yaml", &c).ok());
  expectTable1(c, kPowerplant);
  EXPECT_EQ(c.scene.scene, "plant");
  // The mission section's planning keys: repeatable legs, travel yaw.
  EXPECT_EQ(c.path.iteration_budget, 3000);
  EXPECT_TRUE(c.explorer.travel_yaw);
  EXPECT_DOUBLE_EQ(c.explorer.turn_distance, 4.0);
  EXPECT_EQ(c.explorer.min_visible, 1);
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
}

// Every YAML file under config/ loads and validates (a key misspelt there
// would stop a user's run), and the two scenes of Table 2 carry Table 1's
// parameters and the settings the README's figures were measured with.
TEST(MissionConfig, EveryShippedConfigLoadsAndTable2ScenesKeepTheirSettings) {
  std::map<std::string, MissionConfig> configs;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(NBV_SOURCE_DIR) + "/config")) {
    if (entry.path().extension() != ".yaml") continue;
    MissionConfig c;
    const Status loaded = loadMissionConfig(entry.path().string(), &c);
    ASSERT_TRUE(loaded.ok()) << entry.path() << ": " << loaded.message();
    EXPECT_TRUE(c.validate().ok()) << entry.path() << ": " << c.validate().message();
    configs[entry.path().stem().string()] = c;
  }
  for (const char* name : {"box", "sphere", "room", "plant", "powerplant", "statue"}) {
    EXPECT_EQ(configs.count(name), 1u) << name;
  }
  ASSERT_EQ(configs.count("statue"), 1u);
  ASSERT_EQ(configs.count("powerplant"), 1u);
  const MissionConfig& statue = configs["statue"];
  const MissionConfig& plant = configs["powerplant"];
  expectTable1(statue, kStatue);
  expectTable1(plant, kPowerplant);
  // Both mesh a layer with the drop-off and voxels of a third (the plant's)
  // or half (the statue's) of the planning map's, both plan on 3 voxels with
  // full weights, both tours keep viewpoints that see 3 ISEs.
  EXPECT_DOUBLE_EQ(plant.tsdf.mesh_truncation, 0.6);
  EXPECT_DOUBLE_EQ(plant.tsdf.meshLayerConfig().voxel_size, 0.1);
  // The built-in plant (the main command's scene) meshes as the power plant
  // does (session 28: 99.62 against 88.60 % over the same flight).
  const MissionConfig& built_in = configs["plant"];
  EXPECT_DOUBLE_EQ(built_in.tsdf.meshLayerConfig().voxel_size, 0.1);
  EXPECT_TRUE(built_in.tsdf.meshLayerConfig().weight_dropoff);
  EXPECT_DOUBLE_EQ(statue.tsdf.mesh_truncation, 0.45);
  EXPECT_DOUBLE_EQ(statue.tsdf.meshLayerConfig().voxel_size, 0.075);
  for (const MissionConfig* c : {&statue, &plant}) {
    EXPECT_TRUE(c->tsdf.hasMeshLayer());
    EXPECT_TRUE(c->tsdf.meshLayerConfig().weight_dropoff);
    EXPECT_TRUE(c->tsdf.meshLayerConfig().band_allocation);
    EXPECT_FALSE(c->tsdf.band_allocation);
    EXPECT_FALSE(c->tsdf.weight_dropoff);
    EXPECT_DOUBLE_EQ(c->tsdf.truncationDistance(), 3.0 * c->tsdf.voxel_size);
    EXPECT_EQ(c->explorer.min_visible, 3);
    EXPECT_TRUE(c->surface.unknown_fraction);  // pool_unknown_below reads the rays
  }
  // Both fly the tour viewpoint with the best |C_q| u exp(-lambda_tc d) of the
  // whole tour first (session 25).
  for (const MissionConfig* c : {&statue, &plant}) {
    EXPECT_TRUE(c->explorer.head_unknown);
    EXPECT_GE(c->explorer.head_lookahead, 1000);
  }
  // The statue's comparison counts a climb twice (session 26).
  EXPECT_DOUBLE_EQ(statue.explorer.head_vertical_scale, 2.0);
  // The plant's camera is mounted as RotorS's VI-sensor, the statue's level
  // (session 27); the planner and the renderer share the mount.
  EXPECT_DOUBLE_EQ(plant.camera.pitch_deg, 5.73);
  EXPECT_DOUBLE_EQ(plant.surface.camera.pitch_deg, 5.73);
  EXPECT_DOUBLE_EQ(statue.camera.pitch_deg, 0.0);
}

// The view rays (Viewpoint::unknown_fraction) are cast only for an option
// that reads them: pool_unknown_below, or head_unknown with a lookahead.
TEST(MissionConfig, CastsTheViewRaysOnlyForAnOptionThatReadsThem) {
  auto load = [](const std::string& mission_keys) {
    MissionConfig c;
    EXPECT_TRUE(loadMissionConfig(writeTemp("rays.yaml", "mission:\n" + mission_keys), &c).ok()) << mission_keys;
    return c.surface.unknown_fraction;
  };
  EXPECT_FALSE(load("  min_visible: 3\n"));
  EXPECT_TRUE(load("  pool_unknown_below: 0.05\n"));
  EXPECT_TRUE(load("  head_lookahead: 10\n  head_unknown: true\n"));
  EXPECT_FALSE(load("  head_unknown: true\n"));  // no lookahead: nothing ranks
}

TEST(MissionConfig, ReadsTheHeadRankingsDecay) {
  MissionConfig c;
  ASSERT_TRUE(loadMissionConfig(writeTemp("lambda.yaml", "mission:\n  head_lookahead: 10\n  head_lambda: 0.4\n"
                                                         "  head_vertical_scale: 2.0\n"),
                                &c)
                  .ok());
  EXPECT_DOUBLE_EQ(c.explorer.head_lambda, 0.4);
  EXPECT_DOUBLE_EQ(c.explorer.head_vertical_scale, 2.0);
  ASSERT_TRUE(loadMissionConfig(writeTemp("lambda_nan.yaml", "mission:\n  head_lambda: .nan\n"), &c).ok());
  EXPECT_NE(c.validate().message().find("head_lambda"), std::string::npos) << c.validate().message();
}

TEST(MissionConfig, ReadsTheCameraMountsPitch) {
  MissionConfig c;
  ASSERT_TRUE(loadMissionConfig(writeTemp("pitch.yaml", "nbv:\n  camera: {pitch_deg: 5.73}\n"), &c).ok());
  EXPECT_DOUBLE_EQ(c.camera.pitch_deg, 5.73);
  EXPECT_DOUBLE_EQ(c.surface.camera.pitch_deg, 5.73);  // eq. 2 and C_q use the same mount
  EXPECT_DOUBLE_EQ(c.explorer.gaze.camera.pitch_deg, 5.73);
  EXPECT_TRUE(c.validate().ok());
  ASSERT_TRUE(loadMissionConfig(writeTemp("pitch_far.yaml", "nbv:\n  camera: {pitch_deg: 75.0}\n"), &c).ok());
  EXPECT_NE(c.validate().message().find("camera/pitch_deg"), std::string::npos) << c.validate().message();
}

TEST(MissionConfig, ReadsTheScenesUpAxisAndFit) {
  MissionConfig c;
  ASSERT_TRUE(loadMissionConfig(writeTemp("fit.yaml", "depth_sim:\n  scene: statue\n  scene_up_axis: y\n"
                                                      "  scene_fit_size: [20, 20, 60]\n"),
                                &c)
                  .ok());
  EXPECT_EQ(c.scene.transform.up_axis, "y");
  EXPECT_EQ(c.scene.transform.fit_size, Eigen::Vector3d(20, 20, 60));
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
  c = MissionConfig();
  ASSERT_TRUE(loadMissionConfig(writeTemp("fit_scaled.yaml", "depth_sim:\n  scene_scale: 0.5\n"
                                                             "  scene_fit_size: [20, 20, 60]\n"),
                                &c)
                  .ok());
  EXPECT_NE(c.validate().message().find("scale"), std::string::npos) << c.validate().message();
}

TEST(MissionConfig, RefusesUnknownKeysWrongTypesAndMissingFiles) {
  MissionConfig c;
  Status s = loadMissionConfig(writeTemp("typo.yaml", "mission:\n  sped: 0.5\n"), &c);
  EXPECT_NE(s.message().find("mission/sped is not a known key"), std::string::npos) << s.message();
  s = loadMissionConfig(writeTemp("type.yaml", "nbv:\n  voxel_size: [1, 2]\n"), &c);
  EXPECT_NE(s.message().find("nbv/voxel_size has the wrong type"), std::string::npos) << s.message();
  s = loadMissionConfig(writeTemp("start.yaml", "mission:\n  start: [1, 2, 3]\n"), &c);
  EXPECT_NE(s.message().find("mission/start expected [x, y, z, yaw]"), std::string::npos) << s.message();
  s = loadMissionConfig(writeTemp("objective.yaml", "mission:\n  tour_objective: total\n"), &c);
  EXPECT_NE(s.message().find("mission/tour_objective expected 'product' or 'sum'"), std::string::npos)
      << s.message();
  c = MissionConfig();
  ASSERT_TRUE(loadMissionConfig(writeTemp("sum.yaml", "mission:\n  tour_objective: sum\n"), &c).ok());
  EXPECT_EQ(c.explorer.graph.objective, TourObjective::kSum);
  s = loadMissionConfig("/nonexistent/mission.yaml", &c);
  EXPECT_NE(s.message().find("cannot read"), std::string::npos) << s.message();
  c = MissionConfig();
  ASSERT_TRUE(loadMissionConfig(writeTemp("queue.yaml", "mission:\n  mesh_layer_queue: 8\n"), &c).ok());
  EXPECT_EQ(c.mesh_layer_queue, 8);
  c.mesh_layer_queue = 0;
  EXPECT_NE(c.validate().message().find("mission/mesh_layer_queue"), std::string::npos);
  c = MissionConfig();
  c.start = Eigen::Vector4d(100, 0, 2, 0);
  EXPECT_NE(c.validate().message().find("mission/start"), std::string::npos);
}

// The tracker section sets the simulated UAV's limits (the model's, which its
// MPC plans with), and the legs' reference may not ask for more than they allow.
TEST(MissionConfig, TrackerLimitsBoundTheLegsReference) {
  MissionConfig c;
  ASSERT_TRUE(loadMissionConfig(writeTemp("yaw2.yaml", "tracker:\n  yaw_rate_max: 2.0\n  v_max: 0.8\n"
                                                       "mission:\n  yaw_rate: 2.0\n"), &c).ok());
  EXPECT_DOUBLE_EQ(c.tracker.model.yaw_rate_max, 2.0);
  EXPECT_DOUBLE_EQ(c.tracker.model.v_max, 0.8);
  EXPECT_DOUBLE_EQ(c.tracker.model.a_max, UavModelConfig().a_max);
  EXPECT_DOUBLE_EQ(MpcTracker(c.tracker.mpc, c.tracker.model).model().v_max, 0.8);
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
  c = MissionConfig();
  ASSERT_TRUE(loadMissionConfig(writeTemp("fast_yaw.yaml", "mission:\n  yaw_rate: 2.0\n"), &c).ok());
  EXPECT_NE(c.validate().message().find("mission/yaw_rate expected <= tracker/yaw_rate_max"), std::string::npos)
      << c.validate().message();
  c = MissionConfig();
  ASSERT_TRUE(loadMissionConfig(writeTemp("fast.yaml", "tracker:\n  v_max: 0.4\n"), &c).ok());
  EXPECT_NE(c.validate().message().find("mission/speed expected <= tracker/v_max"), std::string::npos)
      << c.validate().message();
  Status s = loadMissionConfig(writeTemp("tracker_typo.yaml", "tracker:\n  yaw_rate: 2.0\n"), &c);
  EXPECT_NE(s.message().find("tracker/yaw_rate is not a known key"), std::string::npos) << s.message();
  c = MissionConfig();
  ASSERT_TRUE(loadMissionConfig(writeTemp("slow.yaml", "tracker:\n  a_max: -1\n"), &c).ok());
  EXPECT_NE(c.validate().message().find("a_max"), std::string::npos) << c.validate().message();
}

TEST(MissionConfig, ReadsTheTruncationDistanceAndRefusesOneBelowAVoxel) {
  MissionConfig c;
  ASSERT_TRUE(loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/plant.yaml", &c).ok());
  EXPECT_DOUBLE_EQ(c.tsdf.truncationDistance(), 3.0 * c.tsdf.voxel_size);  // no key: 3 voxels
  c = MissionConfig();
  ASSERT_TRUE(loadMissionConfig(writeTemp("trunc.yaml", "nbv:\n  voxel_size: 0.3\n  truncation: 0.6\n"), &c).ok());
  EXPECT_DOUBLE_EQ(c.tsdf.truncationDistance(), 0.6);
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
  c = MissionConfig();
  ASSERT_TRUE(loadMissionConfig(writeTemp("thin.yaml", "nbv:\n  voxel_size: 0.3\n  truncation: 0.1\n"), &c).ok());
  EXPECT_NE(c.validate().message().find("truncation"), std::string::npos) << c.validate().message();
}

// A whole mission on the 4 m box: it must end by itself (no ISE of C_ins
// left) with the box's surface observed, and repeat exactly.
TEST(Mission, BoxMissionCompletesByItselfAndObservesTheBox) {
  BoxMission box;
  ASSERT_NO_FATAL_FAILURE(loadBoxMission(&box));
  MissionConfig& c = box.config;
  const TriangleMesh& mesh = box.mesh;
  const RaycastScene& scene = *box.scene;
  SurfaceCloud cloud;
  ASSERT_TRUE(SurfaceSampler(0.2, 3).sample(mesh, 100000, &cloud).ok());
  std::vector<Eigen::Vector3d> probe;
  for (const Eigen::Vector3f& p : cloud.points)
    if (p.z() > 0.05) probe.push_back(p.cast<double>());  // the ground under the box is never seen
  MissionRunner runner(c, scene);
  runner.setProbePoints(probe);
  const MissionResult r = runner.run();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  EXPECT_TRUE(r.completed) << r.end_reason;
  ASSERT_FALSE(r.events.empty());
  const double observed = r.events.back().observed;
  std::printf("box mission: %.1f s of flight, %.1f m, %zu frames, %zu updates, observed %.1f %%, wall %.1f s\n",
              r.flight_time, r.path_length, r.frames, r.frontier_updates, 100.0 * observed, r.wall_time);
  EXPECT_GT(observed, 0.5);
  // The real figure: nbv_evaluate's coverage of the reconstructed mesh.
  MeshExtractor mesher;
  mesher.update(runner.map());
  const EvalConfig eval = boxEvalConfig(c);
  EvalResult e;
  ASSERT_TRUE(Evaluator(eval).evaluate(mesh, mesher.mesh(), &e).ok());
  std::printf("box mission coverage %.2f %%, RMSE %.2f cm\n", 100.0 * e.coverage.coverage(), 100.0 * e.error_stats.rmse);
  EXPECT_GT(e.coverage.coverage(), 0.95);
  EXPECT_LT(e.error_stats.rmse, c.tsdf.voxel_size);
  EXPECT_GT(r.path_length, 5.0);
  EXPECT_LT(r.flight_time, c.max_flight_time);

  EXPECT_EQ(&runner.meshMap(), &runner.map());  // no mesh_truncation: the map itself

  // The repeat also fuses a mesh layer with a shorter truncation: the flight
  // must not change (planning never reads it), and its mesh covers the box.
  MissionConfig layered = c;
  layered.tsdf.mesh_truncation = 2.0 * c.tsdf.voxel_size;
  MissionRunner again(layered, scene);
  // With the coverage over time (nbv_mission --coverage-every): every 20 s of
  // flight and at the end, the layer holds every frame up to then.
  struct Checkpoint {
    double t, path_length;
    TriangleMesh mesh;
  };
  std::vector<Checkpoint> checkpoints;
  again.setCheckpoints(20.0, [&](double t, double path_length, const TsdfMap& mesh_map) {
    MeshExtractor m;
    m.update(mesh_map);
    checkpoints.push_back({t, path_length, m.mesh()});
  });
  const MissionResult r2 = again.run();
  ASSERT_EQ(r2.flown.size(), r.flown.size());
  for (size_t i = 0; i < r.flown.size(); ++i) ASSERT_EQ(r2.flown[i], r.flown[i]) << "frame " << i;
  ASSERT_NE(&again.meshMap(), &again.map());
  EXPECT_DOUBLE_EQ(again.meshMap().config().truncationDistance(), 2.0 * c.tsdf.voxel_size);
  EXPECT_DOUBLE_EQ(again.map().config().truncationDistance(), 3.0 * c.tsdf.voxel_size);
  MeshExtractor layer_mesher;
  layer_mesher.update(again.meshMap());
  EvalResult e2;
  ASSERT_TRUE(Evaluator(eval).evaluate(mesh, layer_mesher.mesh(), &e2).ok());
  std::printf("box mission, mesh layer: coverage %.2f %%, RMSE %.2f cm\n", 100.0 * e2.coverage.coverage(),
              100.0 * e2.error_stats.rmse);
  EXPECT_GT(e2.coverage.coverage(), 0.95);
  EXPECT_LT(e2.error_stats.rmse, c.tsdf.voxel_size);

  // The checkpoints: one per 20 s of flight, at the first frame from then
  // on, and one at the end whose mesh is the trial's; scored against one
  // prepared ground truth they give what evaluate() gives.
  ASSERT_GE(checkpoints.size(), 3u);
  const double frame_dt = 1.0 / c.frame_rate;
  for (size_t k = 0; k + 1 < checkpoints.size(); ++k) {
    EXPECT_GE(checkpoints[k].t, 20.0 * (k + 1) - 1e-6) << k;
    EXPECT_LT(checkpoints[k].t, 20.0 * (k + 1) + frame_dt + 1e-6) << k;
    EXPECT_LE(checkpoints[k].path_length, checkpoints[k + 1].path_length) << k;
  }
  EXPECT_DOUBLE_EQ(checkpoints.back().t, r2.flight_time);
  EXPECT_DOUBLE_EQ(checkpoints.back().path_length, r2.path_length);
  EXPECT_EQ(checkpoints.back().mesh.numTriangles(), layer_mesher.mesh().numTriangles());
  EvalResult prepared;
  ASSERT_TRUE(Evaluator(eval).prepareGroundTruth(mesh, &prepared).ok());
  double first = -1.0;
  for (const Checkpoint& cp : checkpoints) {
    ASSERT_TRUE(Evaluator(eval).scoreReconstruction(cp.mesh, &prepared).ok());
    if (first < 0.0) first = prepared.coverage.coverage();
  }
  EXPECT_EQ(prepared.coverage.num_covered, e2.coverage.num_covered);
  EXPECT_EQ(prepared.coverage.visible, e2.coverage.visible);
  EXPECT_DOUBLE_EQ(prepared.error_stats.rmse, e2.error_stats.rmse);
  EXPECT_LT(first, 0.9 * e2.coverage.coverage());  // 20 s in, far from done
  EvalResult unprepared;
  EXPECT_FALSE(Evaluator(eval).scoreReconstruction(checkpoints.back().mesh, &unprepared).ok());
}

// A camera mounted 0.1 rad down, as RotorS's VI-sensor: the same mission
// flies otherwise (the pitch reaches the renderer and the planner) and still
// completes the box.
TEST(Mission, APitchedCameraCompletesTheBox) {
  BoxMission box;
  ASSERT_NO_FATAL_FAILURE(loadBoxMission(&box));
  const MissionConfig& c = box.config;
  MissionConfig pitched = c;
  pitched.camera.pitch_deg = pitched.surface.camera.pitch_deg = pitched.explorer.gaze.camera.pitch_deg = 5.73;
  ASSERT_TRUE(pitched.validate().ok());
  MissionRunner level_runner(c, *box.scene), pitched_runner(pitched, *box.scene);
  const MissionResult level = level_runner.run(), r = pitched_runner.run();
  ASSERT_TRUE(r.status.ok()) << r.status.message();
  EXPECT_TRUE(r.completed) << r.end_reason;
  EXPECT_NE(r.flown, level.flown);
  MeshExtractor mesher;
  mesher.update(pitched_runner.map());
  const EvalConfig eval = boxEvalConfig(c);
  EvalResult e;
  ASSERT_TRUE(Evaluator(eval).evaluate(box.mesh, mesher.mesh(), &e).ok());
  std::printf("box mission, camera 5.73 deg down: %.1f m, coverage %.2f %%, RMSE %.2f cm\n", r.path_length,
              100.0 * e.coverage.coverage(), 100.0 * e.error_stats.rmse);
  EXPECT_GT(e.coverage.coverage(), 0.95);
  EXPECT_LT(e.error_stats.rmse, c.tsdf.voxel_size);
}

}  // namespace
