// Error statistics, the M3C2 cylinder, PLY clouds and the report files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "eval_test_helpers.h"
#include "surface_nbv/eval/error_stats.h"
#include "surface_nbv/eval/m3c2_distance.h"
#include "surface_nbv/eval/report_writer.h"
#include "surface_nbv/sim/procedural_scenes.h"

namespace surface_nbv {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector3f;

const float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(ErrorStats, MomentsAndNumpyPercentilesSkippingNaN) {
  const ErrorStats s = ErrorStats::of({1.0f, kNaN, -2.0f, 3.0f, 4.0f});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.mean, 1.5);
  EXPECT_DOUBLE_EQ(s.std_dev, std::sqrt(5.25));  // population: ((0.25 + 12.25 + 2.25 + 6.25) / 4)
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(7.5));      // sqrt((1 + 4 + 9 + 16) / 4)
  EXPECT_DOUBLE_EQ(s.mean_abs, 2.5);
  EXPECT_DOUBLE_EQ(s.max_abs, 4.0);
  EXPECT_DOUBLE_EQ(s.p25, 0.25);  // numpy.percentile([-2, 1, 3, 4], 25)
  EXPECT_DOUBLE_EQ(s.p50, 2.0);
  EXPECT_DOUBLE_EQ(s.p75, 3.25);
  EXPECT_DOUBLE_EQ(s.p5, -1.55);
  EXPECT_DOUBLE_EQ(s.abs_p95, 3.85);
  const ErrorStats empty = ErrorStats::of({kNaN});
  EXPECT_EQ(empty.count, 0u);
  EXPECT_TRUE(std::isnan(empty.mean));
  EXPECT_TRUE(std::isnan(empty.p50));
}

// A regular grid of `n` x `n` points spaced `step` in the plane z = height,
// normals +z, plus a column of points on the line x = y = 0 with normals +x.
SurfaceCloud planeCloud(int n, float step, float height) {
  SurfaceCloud c;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      c.points.emplace_back((i - n / 2) * step, (j - n / 2) * step, height);
      c.normals.push_back(Vector3f::UnitZ());
    }
  }
  for (int k = -5; k <= 5; ++k) {
    c.points.emplace_back(0.0f, 0.0f, height + 0.02f * k);
    c.normals.push_back(Vector3f::UnitX());
  }
  c.triangles.assign(c.points.size(), 0);
  return c;
}

TEST(M3c2Distance, DifferenceOfMeanProjectionsInTheCylinder) {
  EvalConfig config;
  config.projection_radius = 0.1;
  config.max_depth = 0.2;
  const SurfaceCloud reference = planeCloud(41, 0.05f, 0.0f), compared = planeCloud(41, 0.05f, 0.07f);
  const PointIndex reference_index(reference.points), compared_index(compared.points);
  const M3c2Distance m3c2(config);
  // The perpendicular column is ignored by the normal test: exactly 7 cm.
  EXPECT_FLOAT_EQ(m3c2.at(Vector3f::Zero(), Vector3f::UnitZ(), reference, reference_index, compared, compared_index),
                  0.07f);
  // Beyond max_depth the compared plane is out of the cylinder: no distance.
  const SurfaceCloud far = planeCloud(41, 0.05f, 0.25f);
  const PointIndex far_index(far.points);
  EXPECT_TRUE(std::isnan(m3c2.at(Vector3f::Zero(), Vector3f::UnitZ(), reference, reference_index, far, far_index)));
  // Accepting every normal lets the column in: its points average to the plane's height.
  config.normal_agreement_deg = 90.0;
  const float all = M3c2Distance(config).at(Vector3f::Zero(), Vector3f::UnitZ(), reference, reference_index, compared,
                                            compared_index);
  EXPECT_NEAR(all, 0.07f, 1e-6f);
  // Too few neighbours: none.
  config.min_neighbours = 100;
  EXPECT_TRUE(std::isnan(M3c2Distance(config).at(Vector3f::Zero(), Vector3f::UnitZ(), reference, reference_index,
                                                 compared, compared_index)));
  // compute() fills core points only.
  std::vector<uint8_t> core(reference.size(), 0);
  core[41 * 20 + 20] = 1;
  const std::vector<float> d = m3c2.compute(reference, reference_index, compared, compared_index, core);
  EXPECT_FLOAT_EQ(d[41 * 20 + 20], 0.07f);
  EXPECT_TRUE(std::isnan(d[0]));
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(PlyCloudWriter, WritesBinaryVerticesWithColourAndScalar) {
  const std::string path = (fs::temp_directory_path() / "surface_nbv_test_cloud.ply").string();
  PlyCloud cloud;
  cloud.points = {{1.0f, 2.0f, 3.0f}, {-1.0f, 0.5f, 0.25f}};
  cloud.colors = {Rgb{255, 0, 10}, Rgb{1, 2, 3}};
  cloud.scalar_name = "error";
  cloud.scalars = {0.5f, -0.25f};
  ASSERT_TRUE(writePlyCloud(path, cloud));
  const std::string data = readFile(path);
  const size_t body = data.find("end_header\n") + 11;
  ASSERT_NE(body, std::string::npos + 11);
  EXPECT_NE(data.find("format binary_little_endian 1.0\n"), std::string::npos);
  EXPECT_NE(data.find("element vertex 2\n"), std::string::npos);
  EXPECT_NE(data.find("property float error\n"), std::string::npos);
  EXPECT_EQ(data.find("property float nx"), std::string::npos);
  ASSERT_EQ(data.size() - body, 2u * (12 + 3 + 4));
  float x = 0.0f, e = 0.0f;
  std::memcpy(&x, data.data() + body + 19, 4);
  std::memcpy(&e, data.data() + body + 19 + 15, 4);
  EXPECT_EQ(x, -1.0f);
  EXPECT_EQ(e, -0.25f);
  EXPECT_EQ(static_cast<uint8_t>(data[body + 12]), 255);
  cloud.colors.pop_back();
  EXPECT_FALSE(writePlyCloud(path, cloud));
  EXPECT_FALSE(writePlyCloud("/nonexistent-dir/cloud.ply", PlyCloud()));
  fs::remove(path);
}

TEST(ReportWriter, ErrorColoursRunFromBlueThroughGreyToRed) {
  EXPECT_EQ(ReportWriter::errorColour(-1.0, 0.1), (Rgb{59, 76, 192}));
  EXPECT_EQ(ReportWriter::errorColour(0.0, 0.1), (Rgb{221, 221, 221}));
  EXPECT_EQ(ReportWriter::errorColour(0.1, 0.1), (Rgb{180, 4, 38}));
  EXPECT_EQ(ReportWriter::errorColour(0.05, 0.1), (Rgb{201, 113, 130}));
}

size_t plyVertices(const std::string& path) {
  const std::string data = readFile(path);
  const size_t at = data.find("element vertex ");
  return at == std::string::npos ? 0 : std::stoul(data.substr(at + 15));
}

TEST(ReportWriter, WritesReportsAndCloudsThatAddUp) {
  TriangleMesh box;
  ASSERT_TRUE(makeProceduralScene("box", &box));
  const TriangleMesh shifted = eval_test::gridBox(eval_test::boxLo() - Eigen::Vector3d::Constant(0.02),
                                                  eval_test::boxHi() + Eigen::Vector3d::Constant(0.02), 1.0);
  TriangleMesh half = shifted;
  half.triangles.resize(half.triangles.size() / 2);  // the +x, -x and +y faces
  EvalConfig config;
  EvalResult result;
  ASSERT_TRUE(Evaluator(config).evaluate(box, half, &result));
  const std::string dir = (fs::temp_directory_path() / "surface_nbv_test_report").string();
  fs::remove_all(dir);
  ASSERT_TRUE(ReportWriter(result, {"half.ply", "box"}).write(dir));
  EXPECT_EQ(plyVertices(dir + "/ground_truth_visible.ply"), result.numVisible());
  EXPECT_EQ(plyVertices(dir + "/ground_truth_hidden.ply"), result.numHidden());
  EXPECT_EQ(plyVertices(dir + "/coverage.ply"), result.numVisible());
  EXPECT_EQ(plyVertices(dir + "/error.ply"), result.matched);
  EXPECT_GT(result.matched, 0u);
  const std::string json = readFile(dir + "/report.json");
  for (const char* key :
       {"\"coverage_percent\"", "\"rmse\"", "\"std_dev\"", "\"ground_truth_triangles\": 12",
        "\"reconstruction\": \"half.ply\"", "\"e_max_m\": 0.2598076211", "\"abs_p95\"", "\"ground_truth\": 9600,"}) {
    EXPECT_NE(json.find(key), std::string::npos) << key << " missing from\n" << json;
  }
  EXPECT_NE(json.find("\"visible\": " + std::to_string(result.numVisible()) + ","), std::string::npos);
  EXPECT_NE(json.find("\"hidden\": " + std::to_string(result.numHidden()) + ","), std::string::npos);
  const std::string md = readFile(dir + "/report.md");
  EXPECT_NE(md.find("| surface coverage |"), std::string::npos);
  EXPECT_NE(md.find("e_max = rho_v sqrt(3) / 2 = 25.98 cm"), std::string::npos) << md;
  EXPECT_NE(md.find("| M3C2 mean error | 2.00 cm |"), std::string::npos) << md;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace surface_nbv
