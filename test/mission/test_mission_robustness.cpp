// Issue #40: a mission with a real sensor (VI-sensor-like stereo noise,
// lateral noise, dropouts, millimetres) and drifting odometry still ends by
// itself on a small scene, and its reconstruction stays close to the truth.
#include "surface_nbv/mission/mission_runner.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "surface_nbv/eval/evaluator.h"
#include "surface_nbv/map/mesh_extractor.h"

using namespace surface_nbv;

namespace {

// config/box.yaml with legs bounded by roadmap samples (a repeatable flight).
MissionConfig boxConfig() {
  MissionConfig c;
  EXPECT_TRUE(loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/box.yaml", &c).ok());
  c.progress_period = 60.0;
  c.path.iteration_budget = 20000;
  c.path.time_budget = 60.0;
  return c;
}

// The VI-sensor row of scripts/robustness on the box's camera.
void makeReal(MissionConfig* c) {
  c->camera.noise_k = 0.007;
  c->camera.sensor.lateral_noise_px = 0.5;
  c->camera.sensor.grazing_dropout_deg = 75.0;
  c->camera.sensor.dropout_rate = 0.01;
  c->camera.sensor.quantization = 0.001;
  c->surface.camera = c->camera;
  c->explorer.gaze.camera = c->camera;
  c->pose_error.drift_rate = 0.005;
  c->pose_error.yaw_drift_deg = 0.05;
  c->pose_error.jitter_position = 0.005;
  c->pose_error.jitter_angle_deg = 0.05;
}

struct Outcome {
  MissionResult result;
  double coverage = 0.0, rmse = 0.0;
};

Outcome fly(const MissionConfig& c, const TriangleMesh& mesh, const RaycastScene& scene) {
  Outcome o;
  MissionRunner runner(c, scene);
  o.result = runner.run();
  EXPECT_TRUE(o.result.status.ok()) << o.result.status.message();
  MeshExtractor mesher;
  mesher.update(runner.meshMap());
  EvalConfig eval;
  eval.voxel_size = c.tsdf.voxel_size;
  eval.min_range = c.camera.min_range;
  eval.max_range = c.camera.max_range;
  eval.threads = 2;
  EvalResult e;
  EXPECT_TRUE(Evaluator(eval).evaluate(mesh, mesher.mesh(), &e).ok());
  o.coverage = e.coverage.coverage();
  o.rmse = e.error_stats.rmse;
  return o;
}

TEST(MissionRobustness, ANoisyDriftingMissionEndsByItselfAndStaysCloseToTheTruth) {
  MissionConfig c = boxConfig();
  makeReal(&c);
  ASSERT_TRUE(c.validate().ok()) << c.validate().message();
  TriangleMesh mesh;
  ASSERT_TRUE(loadScene(c.scene, &mesh).ok());
  std::unique_ptr<RaycastScene> scene;
  ASSERT_TRUE(RaycastScene::create(mesh, &scene).ok());

  const Outcome o = fly(c, mesh, *scene);
  const MissionResult& r = o.result;
  std::printf("noisy box mission: %.1f s of flight, %.1f m, %zu frames, coverage %.2f %%, RMSE %.2f cm, "
              "odometry error %.3f m at the end (RMS %.3f m); %s\n",
              r.flight_time, r.path_length, r.frames, 100.0 * o.coverage, 100.0 * o.rmse, r.pose_error.final_position,
              r.pose_error.rms_position, r.end_reason.c_str());
  EXPECT_TRUE(r.completed) << r.end_reason;  // no ISE of C_ins left: noise made no endless frontier
  EXPECT_LT(r.flight_time, c.max_flight_time);
  EXPECT_EQ(r.pose_error.frames, r.frames);
  EXPECT_GT(r.pose_error.final_position, 0.0);  // the odometry drifted
  EXPECT_GT(o.coverage, 0.9);
  EXPECT_LT(o.rmse, c.tsdf.voxel_size);
}

}  // namespace
