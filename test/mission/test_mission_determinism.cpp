// Determinism of the headless runner (issue #9): the box mission with the
// same seed, one thread and iteration-bounded legs gives the same map (a
// digest of every block) and the same plan (every frontier decision and the
// pose at every frame), run after run; another seed samples other roadmaps
// and so flies another path.
#include "surface_nbv/mission/mission_runner.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "../fuzz/map_digest.h"
#include "surface_nbv/sim/procedural_scenes.h"

using namespace surface_nbv;

namespace {

struct MissionRun {
  MissionResult result;
  uint64_t map_hash = 0;
  uint64_t mesh_hash = 0;  // the mesh layer's map
  size_t known = 0;
};

class MissionDeterminism : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(loadMissionConfig(std::string(NBV_SOURCE_DIR) + "/config/box.yaml", &config_).ok());
    config_.threads = 1;
    // Legs bounded by roadmap samples; the wall-time budget only guards a hung planner.
    config_.path.iteration_budget = 20000;
    config_.path.time_budget = 60.0;
    config_.explorer.tsp.time_limit_s = 0.0;
    config_.progress_period = 1e9;
    ASSERT_TRUE(config_.validate().ok()) << config_.validate().message();
    TriangleMesh mesh;
    ASSERT_TRUE(loadScene(config_.scene, &mesh).ok());
    ASSERT_TRUE(RaycastScene::create(mesh, &scene_).ok());
  }

  MissionRun run(unsigned int seed) const { return run(config_, seed); }
  MissionRun run(const MissionConfig& config, unsigned int seed) const {
    MissionConfig c = config;
    c.seed = seed;
    MissionRunner runner(c, *scene_);
    MissionRun r;
    r.result = runner.run();
    r.map_hash = fuzz::mapDigest(runner.map());
    r.mesh_hash = fuzz::mapDigest(runner.meshMap());
    for (const auto& block : runner.map().blocks()) {
      for (const TsdfVoxel& v : block->voxels) r.known += runner.map().stateOf(v) != VoxelState::kUnknown ? 1 : 0;
    }
    std::printf("seed %u: map hash %016llx, %zu known voxels, %zu frames, %zu decisions, %.1f m, %.1f s of flight, "
                "%s, wall %.1f s\n",
                seed, static_cast<unsigned long long>(r.map_hash), r.known, r.result.frames, r.result.events.size(),
                r.result.path_length, r.result.flight_time, r.result.end_reason.c_str(), r.result.wall_time);
    return r;
  }

  MissionConfig config_;
  std::unique_ptr<RaycastScene> scene_;
};

// Every decision of the Explorer, in order, with what it saw.
void expectSameDecisions(const MissionResult& a, const MissionResult& b) {
  ASSERT_EQ(a.events.size(), b.events.size());
  for (size_t i = 0; i < a.events.size(); ++i) {
    const MissionEvent &x = a.events[i], &y = b.events[i];
    EXPECT_EQ(x.t, y.t) << "decision " << i;
    EXPECT_EQ(x.path_length, y.path_length) << "decision " << i;
    EXPECT_EQ(x.action, y.action) << "decision " << i;
    EXPECT_EQ(x.reason, y.reason) << "decision " << i;
    EXPECT_EQ(x.ises, y.ises) << "decision " << i;
    EXPECT_EQ(x.viewpoints, y.viewpoints) << "decision " << i;
    EXPECT_EQ(x.clusters, y.clusters) << "decision " << i;
    EXPECT_EQ(x.tour, y.tour) << "decision " << i;
  }
}

TEST_F(MissionDeterminism, SameSeedGivesTheSameMapAndPlanAnotherSeedAnotherPath) {
  const MissionRun first = run(1), second = run(1);
  ASSERT_TRUE(first.result.status.ok()) << first.result.status.message();
  ASSERT_TRUE(second.result.status.ok()) << second.result.status.message();
  EXPECT_TRUE(first.result.completed) << first.result.end_reason;
  EXPECT_EQ(first.map_hash, second.map_hash) << "the same seed gave another map";
  EXPECT_EQ(first.known, second.known);
  EXPECT_EQ(first.result.end_reason, second.result.end_reason);
  EXPECT_EQ(first.result.explorer.legs, second.result.explorer.legs);
  expectSameDecisions(first.result, second.result);
  ASSERT_EQ(first.result.flown.size(), second.result.flown.size());
  for (size_t i = 0; i < first.result.flown.size(); ++i) {
    ASSERT_EQ(first.result.flown[i], second.result.flown[i]) << "frame " << i;
  }

  // The seed drives the roadmap's sampler: the legs, hence the flown path
  // and the map built along it, change with it.
  const MissionRun other = run(2);
  ASSERT_TRUE(other.result.status.ok()) << other.result.status.message();
  bool same_path = other.result.flown.size() == first.result.flown.size();
  for (size_t i = 0; same_path && i < first.result.flown.size(); ++i) {
    same_path = other.result.flown[i] == first.result.flown[i];
  }
  EXPECT_FALSE(same_path) << "seeds 1 and 2 flew the same path";
  EXPECT_NE(other.map_hash, first.map_hash);
}

// The mesh layer fused on its own thread, waiting for every frame or
// lagging up to 64 (mission/mesh_layer_queue): the same flight, the same
// planning map and the same layer.
TEST_F(MissionDeterminism, MeshLayerQueueChangesNeitherTheFlightNorTheMaps) {
  MissionConfig c = config_;
  c.threads = 2;  // the layer fuses behind the caller only with two threads or more
  c.tsdf.mesh_voxel_size = 0.5 * c.tsdf.voxel_size;
  c.tsdf.mesh_truncation = 3.0 * c.tsdf.voxel_size;
  c.mesh_layer_queue = 1;
  ASSERT_TRUE(c.validate().ok()) << c.validate().message();
  const MissionRun waiting = run(c, 1);
  c.mesh_layer_queue = 64;
  const MissionRun lagging = run(c, 1);
  ASSERT_TRUE(waiting.result.status.ok()) << waiting.result.status.message();
  ASSERT_TRUE(lagging.result.status.ok()) << lagging.result.status.message();
  EXPECT_GT(waiting.result.frames, 64u);  // the queue filled up
  EXPECT_NE(waiting.mesh_hash, waiting.map_hash);  // a layer of its own
  EXPECT_EQ(waiting.map_hash, lagging.map_hash);
  EXPECT_EQ(waiting.mesh_hash, lagging.mesh_hash);
  expectSameDecisions(waiting.result, lagging.result);
  EXPECT_EQ(waiting.result.flown, lagging.result.flown);
}

}  // namespace
