// The mesh layer: a second TSDF with its own truncation, fed the same frames.
#include "surface_nbv/map/mesh_layer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "surface_nbv/map/map_io.h"
#include "surface_nbv/map/mesh_extractor.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/mesh_builder.h"

#include "../sim/render_test_helpers.h"  // lookAlong

using namespace surface_nbv;

namespace {

// Optical frame looking along world +x (dir = 1) or -x (dir = -1).
Transform lookingAlongX(const Eigen::Vector3d& position, double dir) {
  Transform T = Transform::Identity();
  T.linear().col(0) = Eigen::Vector3d(0, -dir, 0);
  T.linear().col(1) = Eigen::Vector3d(0, 0, -1);
  T.linear().col(2) = Eigen::Vector3d(dir, 0, 0);
  T.translation() = position;
  return T;
}

constexpr double kFront = 5.0, kBack = 5.2;  // a 0.2 m thick wall across x

TsdfConfig thinWallConfig() {
  TsdfConfig c;
  c.voxel_size = 0.1;  // default truncation: 3 voxels, 0.3 m, more than the wall is thick
  c.bounds = AlignedBox(Eigen::Vector3d(0, -2, -2), Eigen::Vector3d(10.4, 2, 2));
  return c;
}

// Mean distance from the mesh vertices in the middle of the wall to its nearest face.
double wallError(const TriangleMesh& mesh, size_t* vertices) {
  double sum = 0.0;
  *vertices = 0;
  for (const Eigen::Vector3f& v : mesh.vertices) {
    if (std::abs(v.y()) > 1.0 || std::abs(v.z()) > 1.0) continue;
    sum += std::min(std::abs(v.x() - kFront), std::abs(v.x() - kBack));
    ++*vertices;
  }
  return *vertices > 0 ? sum / *vertices : INFINITY;
}

// The box scene b holds, ready for ray casting (null if Embree refused it).
std::unique_ptr<RaycastScene> sceneOf(MeshBuilder* b) {
  std::unique_ptr<RaycastScene> scene;
  if (!RaycastScene::create(b->take(), &scene)) scene.reset();
  return scene;
}

// A planning map with its integrator and a mesh layer of 0.2 m truncation.
struct LayeredMap {
  explicit LayeredMap(const TsdfConfig& config) : map(config), integrator(&map), layer(&map) {}
  TsdfMap map;
  TsdfIntegrator integrator;
  MeshLayer layer;
};

TsdfConfig layeredConfig() {
  TsdfConfig c = thinWallConfig();
  c.mesh_truncation = 0.2;
  return c;
}

DepthCamera smallCamera() {
  CameraConfig cam;
  cam.width = 160;
  cam.height = 120;
  return DepthCamera(cam);
}

}  // namespace

TEST(MeshLayer, WithoutMeshTruncationItIsThePlanningMap) {
  TsdfMap planning(thinWallConfig());
  MeshLayer layer(&planning);
  EXPECT_FALSE(layer.separate());
  EXPECT_EQ(&layer.map(), &planning);
  EXPECT_TRUE(layer.markFree(Eigen::Vector3d(1, 0, 0), 0.5).ok());  // nothing to do
  EXPECT_EQ(planning.numBlocks(), 0u);
  // mesh_truncation equal to the map's own truncation needs no second map either.
  TsdfConfig same = thinWallConfig();
  same.mesh_truncation = same.truncationDistance();
  TsdfMap planning_same(same);
  EXPECT_FALSE(MeshLayer(&planning_same).separate());
}

TEST(MeshLayer, ConfigRefusesAMeshTruncationBelowAVoxel) {
  TsdfConfig c = thinWallConfig();
  for (double bad : {0.05, -0.2, std::nan("")}) {
    c.mesh_truncation = bad;
    EXPECT_NE(c.validate().message().find("mesh_truncation"), std::string::npos) << bad;
  }
  c.mesh_truncation = 0.2;
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
  const TsdfConfig m = c.meshLayerConfig();
  EXPECT_DOUBLE_EQ(m.truncationDistance(), 0.2);
  EXPECT_FALSE(m.hasMeshLayer());
}

// A weight drop-off for the mesh alone asks for a layer of its own, even at
// the map's truncation; without a layer there is nothing to apply it to.
TEST(MeshLayer, WeightDropoffOfTheMeshAloneMakesALayer) {
  TsdfConfig c = thinWallConfig();
  c.mesh_truncation = c.truncationDistance();
  c.mesh_weight_dropoff = true;
  ASSERT_TRUE(c.validate().ok()) << c.validate().message();
  TsdfMap planning(c);
  MeshLayer layer(&planning);
  ASSERT_TRUE(layer.separate());
  EXPECT_TRUE(layer.map().config().weight_dropoff);
  EXPECT_FALSE(layer.map().config().mesh_weight_dropoff);
  EXPECT_FALSE(planning.config().weight_dropoff);  // planning keeps full weights
  EXPECT_DOUBLE_EQ(layer.map().config().truncationDistance(), c.truncationDistance());
  c.mesh_truncation = 0.0;
  EXPECT_NE(c.validate().message().find("mesh_weight_dropoff needs a mesh layer"), std::string::npos)
      << c.validate().message();
}

// A wall thinner than the truncation, seen from both sides: the planning
// map's negative band from each side reaches through to the other face and
// moves both; the layer with 2 voxels keeps the faces where they are.
TEST(MeshLayer, ShorterTruncationKeepsAThinWallsFacesInPlace) {
  MeshBuilder b;
  b.addBox(Eigen::Vector3d(0.5 * (kFront + kBack), 0, 0), Eigen::Vector3d(kBack - kFront, 100.0, 100.0));
  const std::unique_ptr<RaycastScene> scene = sceneOf(&b);
  ASSERT_NE(scene, nullptr);
  const DepthCamera camera = smallCamera();
  const DepthRenderer renderer(*scene, camera, 1);

  LayeredMap m(layeredConfig());
  ASSERT_TRUE(m.layer.separate());
  DepthImage depth;
  for (int k = 0; k < 4; ++k) {  // alternate sides, several distances
    for (double dir : {1.0, -1.0}) {
      const double x = dir > 0 ? 2.0 + 0.3 * k : 8.2 - 0.3 * k;
      const Transform T = lookingAlongX(Eigen::Vector3d(x, 0.05 * k, 0.0), dir);
      renderer.render(T, &depth);
      ASSERT_TRUE(m.integrator.integrateDepth(camera, depth, T).ok());
      ASSERT_TRUE(m.layer.integrateDepth(camera, depth, T).ok());
    }
  }
  MeshExtractor planning_mesh, layer_mesh;
  planning_mesh.update(m.map);
  layer_mesh.update(m.layer.map());
  size_t n_planning = 0, n_layer = 0;
  const double e_planning = wallError(planning_mesh.mesh(), &n_planning);
  const double e_layer = wallError(layer_mesh.mesh(), &n_layer);
  std::printf("thin wall: mean vertex error %.4f m over %zu vertices (truncation 0.3), %.4f m over %zu (0.2)\n",
              e_planning, n_planning, e_layer, n_layer);
  ASSERT_GT(n_layer, 100u);
  EXPECT_LT(e_layer, 0.02);
  EXPECT_LT(e_layer, 0.5 * e_planning);
}

namespace {

// Same blocks with the same voxels, bit for bit.
void expectSameVoxels(const TsdfMap& a, const TsdfMap& b) {
  ASSERT_EQ(a.numBlocks(), b.numBlocks());
  size_t differing = 0;
  for (const auto& block : a.blocks()) {
    const TsdfBlock* other = b.block(block->index);
    ASSERT_NE(other, nullptr) << block->index.transpose();
    for (int i = 0; i < kBlockVoxels; ++i) {
      differing += block->voxels[i].phi != other->voxels[i].phi || block->voxels[i].w != other->voxels[i].w;
    }
  }
  EXPECT_EQ(differing, 0u);
}

// The thin wall with a cube beyond it, for the tests of fusion order.
std::unique_ptr<RaycastScene> wallAndCube() {
  MeshBuilder b;
  b.addBox(Eigen::Vector3d(0.5 * (kFront + kBack), 0, 0), Eigen::Vector3d(kBack - kFront, 1.5, 1.5));
  b.addBox(Eigen::Vector3d(7.5, 0.8, 0.3), Eigen::Vector3d(0.6, 0.6, 0.6));
  return sceneOf(&b);
}

// View k of those tests: from either side in turn, moving a little each time.
Transform alternatingView(int k) {
  const double dir = k % 2 == 0 ? 1.0 : -1.0;
  return lookingAlongX(Eigen::Vector3d(dir > 0 ? 2.0 + 0.2 * k : 9.8 - 0.2 * k, 0.1 * k, 0.05 * k), dir);
}

// The set-up of those tests: the wall and cube, a map fused one frame after
// the other on one thread (`serial`) and one fused the way under test
// (`tested`, whose integrator keeps 3 threads of the caller's own).
struct FusionOrder {
  explicit FusionOrder(const TsdfConfig& config)
      : scene(wallAndCube()), camera(smallCamera()), serial(config), tested(config) {
    tested.integrator.setThreads(3);
  }
  // Renders view k into `depth`, fuses it into `serial` and returns its pose.
  Transform frame(int k) {
    const Transform T = alternatingView(k);
    DepthRenderer(*scene, camera, 1).render(T, &depth);
    EXPECT_TRUE(serial.layer.integrateDepthWith(&serial.integrator, camera, depth, T, 1).ok()) << k;
    return T;
  }

  std::unique_ptr<RaycastScene> scene;
  DepthCamera camera;
  LayeredMap serial, tested;
  DepthImage depth;
};

}  // namespace

// Fusing the planning map and the layer side by side on two threads leaves
// both exactly as fusing them one after the other; a bad frame fails both.
TEST(MeshLayer, SideBySideFusionEqualsOneAfterTheOther) {
  TsdfConfig config = layeredConfig();
  config.threads = 2;
  FusionOrder f(config);
  ASSERT_NE(f.scene, nullptr);
  for (int k = 0; k < 6; ++k) {
    const Transform T = f.frame(k);
    IntegrationStats stats;
    ASSERT_TRUE(f.tested.layer.integrateDepthWith(&f.tested.integrator, f.camera, f.depth, T, 2, &stats).ok());
    EXPECT_GT(stats.voxels_updated, 0u);
  }
  EXPECT_GT(f.serial.map.numBlocks(), 10u);
  expectSameVoxels(f.serial.map, f.tested.map);
  expectSameVoxels(f.serial.layer.map(), f.tested.layer.map());
  EXPECT_EQ(f.tested.integrator.threads(), 3);  // back to the caller's count, not the map's 2

  // A pose outside the bounds: the planning map's error, and the layer's when asked for.
  const Transform outside = lookingAlongX(Eigen::Vector3d(-5.0, 0.0, 0.0), 1.0);
  for (int threads : {1, 2}) {
    Status layer_status;
    LayeredMap& t = f.tested;
    const Status s =
        t.layer.integrateDepthWith(&t.integrator, f.camera, f.depth, outside, threads, nullptr, &layer_status);
    EXPECT_NE(s.message().find("outside the map bounds"), std::string::npos) << threads;
    EXPECT_FALSE(t.layer.integrateDepthWith(&t.integrator, f.camera, f.depth, outside, threads).ok()) << threads;
    if (threads == 2) {
      EXPECT_FALSE(layer_status.ok());
    }
  }
  expectSameVoxels(f.serial.map, f.tested.map);
}

// The layer fused behind the caller (integrateDepthBehind, what nbv_mission
// does) ends voxel for voxel as fused in line, even when the caller
// overwrites its depth image at once; a bad frame is the planning map's
// error at once.
TEST(MeshLayer, FusionBehindEqualsOneAfterTheOther) {
  TsdfConfig config = layeredConfig();
  config.mesh_voxel_size = 0.05;
  FusionOrder f(config);
  ASSERT_NE(f.scene, nullptr);
  for (int k = 0; k < 6; ++k) {
    const Transform T = f.frame(k);
    IntegrationStats stats;
    ASSERT_TRUE(f.tested.layer.integrateDepthBehind(&f.tested.integrator, f.camera, f.depth, T, 2, &stats).ok());
    EXPECT_GT(stats.voxels_updated, 0u);
    std::fill(f.depth.data.begin(), f.depth.data.end(), 1.0f);  // the caller reuses its buffer at once
  }
  ASSERT_TRUE(f.tested.layer.finish().ok());
  EXPECT_GT(f.serial.layer.map().numBlocks(), 10u);
  expectSameVoxels(f.serial.map, f.tested.map);
  expectSameVoxels(f.serial.layer.map(), f.tested.layer.map());
  EXPECT_EQ(f.tested.integrator.threads(), 3);
  const Transform outside = lookingAlongX(Eigen::Vector3d(-5.0, 0.0, 0.0), 1.0);
  const Status s = f.tested.layer.integrateDepthBehind(&f.tested.integrator, f.camera, f.depth, outside, 2);
  EXPECT_NE(s.message().find("outside the map bounds"), std::string::npos) << s.message();
  EXPECT_TRUE(f.tested.layer.finish().ok());  // nothing was left in flight
  expectSameVoxels(f.serial.layer.map(), f.tested.layer.map());
}

// A queue of frames behind (setQueueDepth): the caller goes on while up to
// that many frames wait for the layer, which still takes them all in order.
TEST(MeshLayer, FusionBehindAQueueEqualsOneAfterTheOther) {
  TsdfConfig config = layeredConfig();
  config.mesh_voxel_size = 0.05;
  FusionOrder f(config);
  ASSERT_NE(f.scene, nullptr);
  EXPECT_EQ(f.tested.layer.queueDepth(), 1u);
  f.tested.layer.setQueueDepth(0);
  EXPECT_EQ(f.tested.layer.queueDepth(), 1u);  // at least the frame in flight
  f.tested.layer.setQueueDepth(4);
  for (int k = 0; k < 12; ++k) {
    const Transform T = f.frame(k);
    ASSERT_TRUE(f.tested.layer.integrateDepthBehind(&f.tested.integrator, f.camera, f.depth, T, 2).ok());
    EXPECT_LE(f.tested.layer.pending(), 4u) << k;
    std::fill(f.depth.data.begin(), f.depth.data.end(), 1.0f);  // the caller reuses its buffer at once
  }
  ASSERT_TRUE(f.tested.layer.finish().ok());
  EXPECT_EQ(f.tested.layer.pending(), 0u);
  EXPECT_FALSE(f.tested.layer.busy());
  expectSameVoxels(f.serial.map, f.tested.map);
  expectSameVoxels(f.serial.layer.map(), f.tested.layer.map());
  EXPECT_EQ(f.tested.integrator.threads(), 3);
}

TEST(MeshLayer, ReloadStartsAgainFromTheLoadedFile) {
  TsdfMap planning(layeredConfig());
  TsdfIntegrator integrator(&planning);
  ASSERT_TRUE(integrator.markFree(Eigen::Vector3d(3, 0, 0), 0.8).ok());
  const std::string path = (std::filesystem::temp_directory_path() / "mesh_layer_reload.tsdf").string();
  ASSERT_TRUE(saveMap(planning, path).ok());
  MeshLayer layer(&planning);
  ASSERT_TRUE(layer.markFree(Eigen::Vector3d(7, 0, 0), 0.8).ok());  // something else than the file
  ASSERT_TRUE(layer.reload(path).ok());
  EXPECT_EQ(layer.map().numBlocks(), planning.numBlocks());
  Eigen::Vector3i freed, other;
  ASSERT_TRUE(planning.voxelIndex(Eigen::Vector3d(3, 0, 0), &freed));
  ASSERT_TRUE(planning.voxelIndex(Eigen::Vector3d(7, 0, 0), &other));
  EXPECT_EQ(layer.map().state(freed), VoxelState::kFree);
  EXPECT_EQ(layer.map().state(other), VoxelState::kUnknown);  // the layer's own change is gone
  EXPECT_DOUBLE_EQ(layer.map().config().truncationDistance(), 0.2);
  EXPECT_FALSE(layer.reload("/nonexistent/map.tsdf").ok());
  EXPECT_EQ(layer.map().numBlocks(), planning.numBlocks());  // a refused file changes nothing
  std::filesystem::remove(path);
}

// mesh_voxel_size: a layer of finer voxels than the planning map's, even at
// the planning map's own truncation; the keys that make no sense are refused.
TEST(MeshLayer, FinerVoxelsMakeALayerOfTheirOwn) {
  TsdfConfig c = thinWallConfig();
  c.mesh_truncation = c.truncationDistance();
  c.mesh_voxel_size = 0.05;
  ASSERT_TRUE(c.validate().ok()) << c.validate().message();
  TsdfMap planning(c);
  MeshLayer layer(&planning);
  ASSERT_TRUE(layer.separate());
  EXPECT_DOUBLE_EQ(layer.map().voxelSize(), 0.05);
  EXPECT_DOUBLE_EQ(layer.map().config().truncationDistance(), 0.3);
  EXPECT_DOUBLE_EQ(planning.voxelSize(), 0.1);
  EXPECT_FALSE(layer.map().config().hasMeshLayer());
  // The layer's truncation may be shorter than a planning voxel, not than its own.
  c.mesh_truncation = 0.08;
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
  c.mesh_truncation = 0.04;
  EXPECT_NE(c.validate().message().find("mesh_truncation"), std::string::npos) << c.validate().message();
  c.mesh_truncation = 0.2;
  for (double bad : {-0.05, std::nan("")}) {
    c.mesh_voxel_size = bad;
    EXPECT_NE(c.validate().message().find("mesh_voxel_size expected"), std::string::npos) << bad;
  }
  c.mesh_voxel_size = 0.05;
  c.mesh_truncation = 0.0;
  EXPECT_NE(c.validate().message().find("mesh_voxel_size needs a mesh layer"), std::string::npos)
      << c.validate().message();
}

namespace {

// Mean distance from points along a vertical edge (x0, y0, z in [-1, 1]) to
// the nearest vertex of `mesh`.
double edgeGap(const TriangleMesh& mesh, double x0, double y0) {
  double sum = 0.0;
  int n = 0;
  for (double z = -1.0; z <= 1.0; z += 0.02, ++n) {
    const Eigen::Vector3f p(static_cast<float>(x0), static_cast<float>(y0), static_cast<float>(z));
    float best = INFINITY;
    for (const Eigen::Vector3f& v : mesh.vertices) best = std::min(best, (v - p).squaredNorm());
    sum += std::sqrt(best);
  }
  return sum / n;
}

}  // namespace

// A projective TSDF pulls Marching Cubes' zero crossing into the object at a
// convex edge, by up to a voxel: a layer of half the voxels, fused from the
// same frames, follows a box's edge more closely than the planning map.
TEST(MeshLayer, FinerLayerFollowsAConvexEdge) {
  MeshBuilder b;
  b.addBox(Eigen::Vector3d(5.0, 0.0, 0.0), Eigen::Vector3d(1.0, 1.0, 4.0));
  const std::unique_ptr<RaycastScene> scene = sceneOf(&b);
  ASSERT_NE(scene, nullptr);
  const DepthCamera camera = smallCamera();
  const DepthRenderer renderer(*scene, camera, 1);

  TsdfConfig c = thinWallConfig();
  c.bounds = AlignedBox(Eigen::Vector3d(0, -5, -3), Eigen::Vector3d(10, 5, 3));
  c.mesh_truncation = c.truncationDistance();
  c.mesh_voxel_size = 0.05;
  c.mesh_min_weight = 0.0f;
  ASSERT_TRUE(c.validate().ok()) << c.validate().message();
  LayeredMap m(c);
  ASSERT_TRUE(m.layer.separate());
  const Eigen::Vector3d corner(4.5, -0.5, 0.0);  // the edge facing the cameras
  DepthImage depth;
  for (double deg = 150.0; deg <= 300.0; deg += 15.0) {  // around the corner, 3 m away
    const double a = deg * M_PI / 180.0;
    const Eigen::Vector3d from = corner + 3.0 * Eigen::Vector3d(std::cos(a), std::sin(a), 0.1);
    const Transform T = render_test::lookAlong(from, corner - from);
    renderer.render(T, &depth);
    ASSERT_TRUE(m.layer.integrateDepthWith(&m.integrator, camera, depth, T, 1).ok());
  }
  MeshExtractor planning_mesh, layer_mesh;
  planning_mesh.update(m.map);
  layer_mesh.update(m.layer.map());
  ASSERT_FALSE(planning_mesh.mesh().empty());
  ASSERT_FALSE(layer_mesh.mesh().empty());
  const double coarse = edgeGap(planning_mesh.mesh(), corner.x(), corner.y());
  const double fine = edgeGap(layer_mesh.mesh(), corner.x(), corner.y());
  std::printf("convex edge: mean gap to the mesh %.4f m at 0.1 m voxels, %.4f m at 0.05 m\n", coarse, fine);
  EXPECT_LT(fine, 0.6 * coarse);
  EXPECT_LT(fine, 0.05);
}

// A finer layer cannot read the planning map's file: reload resamples it, so
// the mesh shows the loaded wall in place and the loaded free space is free.
TEST(MeshLayer, ReloadResamplesTheFileForAFinerLayer) {
  MeshBuilder b;
  b.addBox(Eigen::Vector3d(0.5 * (kFront + kBack), 0, 0), Eigen::Vector3d(kBack - kFront, 100.0, 100.0));
  const std::unique_ptr<RaycastScene> scene = sceneOf(&b);
  ASSERT_NE(scene, nullptr);
  const DepthCamera camera = smallCamera();
  const DepthRenderer renderer(*scene, camera, 1);
  TsdfConfig c = thinWallConfig();
  c.mesh_truncation = 0.2;
  c.mesh_voxel_size = 0.05;
  TsdfMap planning(c);
  TsdfIntegrator integrator(&planning);
  DepthImage depth;
  for (int k = 0; k < 3; ++k) {  // the front face only
    const Transform T = lookingAlongX(Eigen::Vector3d(2.0 + 0.3 * k, 0.05 * k, 0.0), 1.0);
    renderer.render(T, &depth);
    ASSERT_TRUE(integrator.integrateDepth(camera, depth, T).ok());
  }
  const std::string path = (std::filesystem::temp_directory_path() / "mesh_layer_resample.tsdf").string();
  ASSERT_TRUE(saveMap(planning, path).ok());
  MeshLayer layer(&planning);
  ASSERT_TRUE(layer.reload(path).ok());
  std::filesystem::remove(path);
  EXPECT_DOUBLE_EQ(layer.map().voxelSize(), 0.05);
  EXPECT_GT(layer.map().numBlocks(), planning.numBlocks());  // 8 fine blocks per coarse one, or fewer
  Eigen::Vector3i in_front, coarse_in_front;
  ASSERT_TRUE(layer.map().voxelIndex(Eigen::Vector3d(4.0, 0.0, 0.0), &in_front));
  ASSERT_TRUE(planning.voxelIndex(Eigen::Vector3d(4.0, 0.0, 0.0), &coarse_in_front));
  ASSERT_EQ(planning.state(coarse_in_front), VoxelState::kFree);
  EXPECT_EQ(layer.map().state(in_front), VoxelState::kFree);
  // The front face where the planning map has it: vertices near x = 5.0.
  MeshExtractor mesher;
  mesher.update(layer.map());
  double sum = 0.0;
  size_t n = 0;
  for (const Eigen::Vector3f& v : mesher.mesh().vertices) {
    if (std::abs(v.y()) > 1.0 || std::abs(v.z()) > 1.0) continue;
    sum += std::abs(v.x() - kFront);
    ++n;
  }
  ASSERT_GT(n, 100u);
  std::printf("resampled layer: %zu vertices, mean distance to the front face %.4f m\n", n, sum / n);
  EXPECT_LT(sum / n, 0.03);
}
