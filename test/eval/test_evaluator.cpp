// The figures of "Tests and figures" in issue 4 on meshes with known geometry:
// identity, a 2 cm shift along the normals, half a mesh, a noisy copy, and
// exact repetition whatever the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "eval_test_helpers.h"
#include "surface_nbv/eval/evaluator.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/sim/procedural_scenes.h"

namespace surface_nbv {
namespace {

using Eigen::Vector3d;
using eval_test::boxHi;
using eval_test::boxLo;
using eval_test::gridBox;

constexpr double kInf = std::numeric_limits<double>::infinity();

EvalConfig testConfig() {
  EvalConfig c;
  c.voxel_size = 0.3;
  c.threads = 2;
  return c;
}

TriangleMesh boxScene() {
  TriangleMesh mesh;
  EXPECT_TRUE(makeProceduralScene("box", &mesh));
  return mesh;
}

// Ground-truth samples off the floor face (the visible ones of a box on the ground).
size_t offTheFloor(const TriangleMesh& ground_truth, const EvalResult& r) {
  size_t n = 0;
  for (int t : r.ground_truth.triangles) {
    const Eigen::Vector3i& tri = ground_truth.triangles[t];
    const Eigen::Vector3f a = ground_truth.vertices[tri[0]], b = ground_truth.vertices[tri[1]],
                          c = ground_truth.vertices[tri[2]];
    n += (b - a).cross(c - a).normalized().z() > -0.5f ? 1 : 0;
  }
  return n;
}

EvalResult evaluate(const TriangleMesh& ground_truth, const TriangleMesh& reconstruction,
                    const EvalConfig& config = testConfig()) {
  EvalResult r;
  const Status s = Evaluator(config).evaluate(ground_truth, reconstruction, &r);
  EXPECT_TRUE(s) << s.message();
  std::printf("coverage %.4f %%, mean %.4f cm, std %.4f cm, RMSE %.4f cm over %zu of %zu visible samples\n",
              100.0 * r.coverage.coverage(), 100.0 * r.error_stats.mean, 100.0 * r.error_stats.std_dev,
              100.0 * r.error_stats.rmse, r.matched, r.numVisible());
  return r;
}

TEST(Evaluator, TheGroundTruthItselfIsFullyCoveredWithZeroError) {
  const TriangleMesh box = boxScene();
  const EvalResult r = evaluate(box, box);
  ASSERT_EQ(r.ground_truth.size(), 9600u);         // 96 m^2 every 0.1 m
  EXPECT_EQ(r.numVisible(), offTheFloor(box, r));  // the floor face is hidden
  EXPECT_NEAR(r.numVisible(), 8000.0, 2.0);
  EXPECT_EQ(r.coverage.num_covered, r.numVisible());
  EXPECT_EQ(r.coverage.coverage(), 1.0);
  EXPECT_EQ(r.matched, r.numVisible());
  EXPECT_EQ(r.error_stats.mean, 0.0);
  EXPECT_EQ(r.error_stats.rmse, 0.0);
}

TEST(Evaluator, ADifferentlyTriangulatedCopyIsFullyCoveredWithZeroError) {
  // Other triangles, so other samples: only the geometry is shared.
  const EvalResult r = evaluate(boxScene(), gridBox(boxLo(), boxHi(), 0.5));
  EXPECT_EQ(r.coverage.coverage(), 1.0);
  EXPECT_GT(r.matched, 0.999 * r.numVisible());  // a corner's cylinder may catch no sample
  EXPECT_LT(std::abs(r.error_stats.mean), 1e-6);
  EXPECT_LT(r.error_stats.rmse, 1e-6);
}

TEST(Evaluator, ACopyShiftedTwoCentimetresAlongTheNormalsGivesTwoCentimetres) {
  const TriangleMesh shifted = gridBox(boxLo() - Vector3d::Constant(0.02), boxHi() + Vector3d::Constant(0.02), 0.5);
  const EvalResult r = evaluate(boxScene(), shifted);
  EXPECT_EQ(r.coverage.coverage(), 1.0);
  EXPECT_GT(r.matched, 0.999 * r.numVisible());
  EXPECT_NEAR(r.error_stats.mean, 0.02, 1e-6);
  EXPECT_LT(r.error_stats.std_dev, 1e-6);
  EXPECT_NEAR(r.error_stats.p5, 0.02, 1e-6);
  EXPECT_NEAR(r.error_stats.p95, 0.02, 1e-6);
  // Shrunk instead: the reconstruction lies behind the surface, the sign flips.
  const TriangleMesh shrunk = gridBox(boxLo() + Vector3d(0.02, 0.02, 0.0), boxHi() - Vector3d::Constant(0.02), 0.5);
  EXPECT_NEAR(evaluate(boxScene(), shrunk).error_stats.mean, -0.02, 1e-6);
}

TEST(Evaluator, PcaNormalsAtTheVoxelScaleKeepTheShift) {
  EvalConfig config = testConfig();
  config.normal_radius = 0.3;
  const TriangleMesh shifted = gridBox(boxLo() - Vector3d::Constant(0.02), boxHi() + Vector3d::Constant(0.02), 0.5);
  const EvalResult r = evaluate(boxScene(), shifted, config);
  EXPECT_EQ(r.coverage.coverage(), 1.0);
  // Near edges the PCA axis tilts and the cylinder sees the neighbouring face.
  EXPECT_NEAR(r.error_stats.mean, 0.02, 1e-3);
  EXPECT_NEAR(r.error_stats.p50, 0.02, 1e-6);
}

TEST(Evaluator, HalfTheMeshGivesHalfTheCoverage) {
  // x <= 0 keeps the -x face and half of the top and the +-y faces: 40 of the
  // 80 m^2 visible, plus the strips of width e_max beyond the cut on three faces.
  const TriangleMesh half = cropMesh(boxScene(), AlignedBox(Vector3d::Constant(-kInf), Vector3d(0.0, kInf, kInf)));
  const EvalConfig config = testConfig();
  const EvalResult r = evaluate(boxScene(), half, config);
  const double expected = (40.0 + 3 * 4.0 * config.eMax()) / 80.0;
  EXPECT_NEAR(r.coverage.coverage(), expected, 0.003);
  EXPECT_NEAR(expected, 0.539, 0.001);
  EXPECT_LT(r.error_stats.rmse, 1e-6);
}

TEST(Evaluator, ANoisyCopyGivesTheNoisesStandardDeviation) {
  // Every vertex of a 0.5 m grid over the box moves along its face's normal
  // by N(0, 3 cm). The surface between vertices interpolates linearly, so its
  // offset field has a smaller spread than the vertices: computed exactly.
  const double sigma = 0.03;
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<double> offsets;
  std::vector<int> face_of;
  const TriangleMesh noisy = gridBox(
      boxLo(), boxHi(), 0.5,
      [&](int, const Vector3d&) {
        offsets.push_back(noise(rng));
        return offsets.back();
      },
      &face_of);
  std::vector<bool> visible_faces(eval_test::kFaces, true);
  visible_faces[eval_test::kBottom] = false;
  double mean = 0.0, std_dev = 0.0;
  eval_test::offsetFieldStats(noisy, offsets, face_of, visible_faces, &mean, &std_dev);
  const EvalResult r = evaluate(boxScene(), noisy);
  std::printf("vertex noise %.2f cm; surface offsets: mean %.3f cm, std %.3f cm\n", 100 * sigma, 100 * mean,
              100 * std_dev);
  EXPECT_EQ(r.coverage.coverage(), 1.0);
  EXPECT_GT(r.matched, 0.99 * r.numVisible());
  EXPECT_NEAR(r.error_stats.std_dev, std_dev, 0.1 * std_dev);
  EXPECT_NEAR(r.error_stats.mean, mean, 0.1 * std_dev);
  EXPECT_NEAR(r.error_stats.rmse, std::hypot(mean, std_dev), 0.1 * std_dev);
}

TEST(Evaluator, RepeatsExactlyWhateverTheThreadCount) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  TriangleMesh plant;
  ASSERT_TRUE(makeProceduralScene("plant", &plant));
  TriangleMesh noisy = plant;
  for (Eigen::Vector3f& v : noisy.vertices) v += Eigen::Vector3f(noise(rng), noise(rng), noise(rng));
  noisy = cropMesh(noisy, AlignedBox(Vector3d(-20, -kInf, -kInf), Vector3d(kInf, kInf, kInf)));
  EvalConfig config = testConfig();
  config.point_spacing = 0.15;
  config.threads = 1;
  const EvalResult one = evaluate(plant, noisy, config);
  for (int threads : {2, 3}) {
    config.threads = threads;
    const EvalResult many = evaluate(plant, noisy, config);
    EXPECT_EQ(one.ground_truth.points, many.ground_truth.points);
    EXPECT_EQ(one.ground_truth.normals, many.ground_truth.normals);
    EXPECT_EQ(one.visible, many.visible);
    EXPECT_EQ(one.coverage.covered, many.coverage.covered);
    ASSERT_EQ(one.error.size(), many.error.size());
    EXPECT_EQ(0, std::memcmp(one.error.data(), many.error.data(), one.error.size() * sizeof(float)));
    EXPECT_EQ(one.error_stats.mean, many.error_stats.mean);
    EXPECT_EQ(one.error_stats.std_dev, many.error_stats.std_dev);
  }
  EXPECT_GT(one.numHidden(), 0u);  // the hall's inside
  EXPECT_GT(one.coverage.coverage(), 0.5);
  EXPECT_LT(one.coverage.coverage(), 0.99);
}

TEST(Evaluator, AnEmptyReconstructionCoversNothingAndAnEmptyGroundTruthIsRefused) {
  const EvalResult r = evaluate(boxScene(), TriangleMesh());
  EXPECT_EQ(r.coverage.coverage(), 0.0);
  EXPECT_EQ(r.numVisible(), offTheFloor(boxScene(), r));
  EXPECT_EQ(r.matched, 0u);
  EXPECT_TRUE(std::isnan(r.error_stats.mean));
  EvalResult unused;
  const Status s = Evaluator(testConfig()).evaluate(TriangleMesh(), boxScene(), &unused);
  EXPECT_FALSE(s);
  EXPECT_NE(s.message().find("ground truth"), std::string::npos);
  EvalConfig bad = testConfig();
  bad.voxel_size = -1.0;
  EXPECT_FALSE(Evaluator(bad).evaluate(boxScene(), boxScene(), &unused));
}

TEST(Evaluator, WithoutPruningEveryGroundTruthSampleCounts) {
  EvalConfig config = testConfig();
  config.prune_hidden = false;
  const EvalResult r = evaluate(boxScene(), boxScene(), config);
  EXPECT_EQ(r.numVisible(), r.ground_truth.size());
  EXPECT_EQ(r.coverage.coverage(), 1.0);
}

}  // namespace
}  // namespace surface_nbv
