// nbv_refuse, the command-line re-fusion of a recorded flight: a circle of
// poses around the box scene fused and evaluated, the mesh layer's
// truncation changing the mesh, the coverage of what the camera saw
// (--observed), and every kind of bad input refused with
// exit code 2 and a message naming it. Also nbv_oracle's flight file, which
// nbv_refuse fuses as a mission's, and its --cover-fraction, and
// nbv_mission's coverage over time (--coverage-every), which nbv_refuse
// reproduces from the flight's first part.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "surface_nbv/sim/mesh_io.h"

using namespace surface_nbv;
namespace fs = std::filesystem;

namespace {

struct ToolRun {
  int code = -1;
  std::string out, err;
};

std::string readText(const fs::path& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The value of a numeric key of refuse.json (a flat object, one key once).
double jsonNumber(const std::string& json, const std::string& key) {
  const size_t at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return NAN;
  return std::strtod(json.c_str() + at + key.size() + 3, nullptr);
}

class NbvRefuse : public ::testing::Test {
 protected:
  void SetUp() override {
    // nbv_refuse is built next to the test executables (devel/lib/surface_nbv).
    exe_ = (fs::read_symlink("/proc/self/exe").parent_path() / "nbv_refuse").string();
    dir_ = fs::path(::testing::TempDir()) / "nbv_refuse_test";
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    config_ = std::string(NBV_SOURCE_DIR) + "/config/box.yaml";
  }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path file = dir_ / name;
    std::ofstream(file) << text;
    return file.string();
  }

  // 40 poses on a circle of radius 5 m around the box (x, y in [-2, 2], z in
  // [0, 4]) at config/box.yaml's start altitude (2 m), facing its axis, the
  // first one at the start pose (-5, 0, 2), 0.2 s apart as nbv_mission writes.
  std::string circlePath() {
    std::ostringstream csv;
    csv << "t_s,x_m,y_m,z_m,yaw_rad\n";
    for (int k = 0; k < 40; ++k) {
      const double a = M_PI + 2.0 * M_PI * k / 40.0;
      csv << 0.2 * k << "," << 5.0 * std::cos(a) << "," << 5.0 * std::sin(a) << ",2," << a + M_PI << "\n";
    }
    return write("circle.csv", csv.str());
  }

  // Runs nbv_refuse, or another tool built beside it.
  ToolRun run(const std::string& arguments, const std::string& tool = "nbv_refuse") {
    const std::string exe = (fs::path(exe_).parent_path() / tool).string();
    const std::string out = (dir_ / "stdout.txt").string(), err = (dir_ / "stderr.txt").string();
    const int status = std::system((exe + " " + arguments + " > " + out + " 2> " + err).c_str());
    ToolRun r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readText(out);
    r.err = readText(err);
    return r;
  }

  std::string exe_, config_;
  fs::path dir_;
};

TEST_F(NbvRefuse, FusesACircleAroundTheBoxAndEvaluatesIt) {
  ASSERT_TRUE(fs::exists(exe_)) << exe_;
  const std::string path = circlePath();
  const fs::path out = dir_ / "plain";
  const ToolRun r = run("--scene box --config " + config_ + " --path " + path + " --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("refused 40 frames: coverage"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("fused 40 / 40 frames (100 %)"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(out / "reconstruction.ply"));
  EXPECT_TRUE(fs::exists(out / "eval" / "report.json"));
  const std::string json = readText(out / "refuse.json");
  EXPECT_EQ(jsonNumber(json, "frames"), 40);
  EXPECT_DOUBLE_EQ(jsonNumber(json, "truncation_m"), 0.3);  // 3 voxels of 0.1 m
  EXPECT_DOUBLE_EQ(jsonNumber(json, "mesh_truncation_m"), 0.3);
  EXPECT_NE(json.find("\"mesh_layer\": false"), std::string::npos) << json;
  // The evaluation sees 80 m^2 of the box: four 16 m^2 sides and the top
  // (the bottom lies on the floor), so the sides alone are 80 %. From 2 m up,
  // 3 m away with a 60 degree vertical field of view, the circle sees every
  // side whole and the top not at all; only a rim of the top is meshed, where
  // the sides' truncation band meets the free space seen over their top edges.
  // Measured 82.77 %.
  const double coverage = jsonNumber(json, "coverage");
  EXPECT_GT(coverage, 0.78) << json;
  EXPECT_LT(coverage, 0.90) << json;
  // A noiseless camera on flat walls: the 10 cm voxels' discretisation only
  // (measured RMSE 1.45 cm, e_max 8.7 cm).
  EXPECT_LT(jsonNumber(json, "rmse_m"), 0.025) << json;
}

TEST_F(NbvRefuse, ObservedCoverageIsWhatTheCameraSaw) {
  ASSERT_TRUE(fs::exists(exe_)) << exe_;
  const std::string path = circlePath();
  const std::string common = "--scene box --config " + config_ + " --path " + path;
  const fs::path plain = dir_ / "plain", observed = dir_ / "observed";
  ASSERT_EQ(run(common + " --out " + plain.string()).code, 0);
  EXPECT_EQ(readText(plain / "refuse.json").find("observed_coverage"), std::string::npos);
  const ToolRun r = run(common + " --observed --out " + observed.string());
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("observed: "), std::string::npos) << r.out;
  const std::string json = readText(observed / "refuse.json");
  // The circle sees the four sides whole (80 % of the visible 80 m^2) and of
  // the top only what lies within e_max (8.7 cm) of the sides' top edges
  // (measured 81.98 %).
  const double seen = jsonNumber(json, "observed_coverage");
  EXPECT_GT(seen, 0.795) << json;
  EXPECT_LT(seen, 0.83) << json;
  EXPECT_GT(jsonNumber(json, "observed_cells"), 10000) << json;
  // The mesh's coverage is what was seen, less what the mesh lost, plus
  // what it covers unseen (the meshed rim of the top).
  const double coverage = jsonNumber(json, "coverage");
  EXPECT_NEAR(coverage, seen - jsonNumber(json, "seen_not_meshed") + jsonNumber(json, "meshed_not_seen"), 1e-6);
  EXPECT_GT(jsonNumber(json, "meshed_not_seen"), 0.0) << json;
  // The fusion does not change: the same mesh as without --observed.
  EXPECT_DOUBLE_EQ(coverage, jsonNumber(readText(plain / "refuse.json"), "coverage"));
}

TEST_F(NbvRefuse, TheMeshTruncationChangesTheMesh) {
  ASSERT_TRUE(fs::exists(exe_)) << exe_;
  const std::string path = circlePath();
  const fs::path plain = dir_ / "plain", layered = dir_ / "layered";
  const std::string common = "--scene box --config " + config_ + " --path " + path;
  ASSERT_EQ(run(common + " --out " + plain.string()).code, 0);
  const ToolRun r = run(common + " --mesh-truncation 0.2 --out " + layered.string());
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const std::string json = readText(layered / "refuse.json");
  EXPECT_NE(json.find("\"mesh_layer\": true"), std::string::npos) << json;
  EXPECT_DOUBLE_EQ(jsonNumber(json, "truncation_m"), 0.3);
  EXPECT_DOUBLE_EQ(jsonNumber(json, "mesh_truncation_m"), 0.2);
  TriangleMesh a, b;
  ASSERT_TRUE(loadMesh((plain / "reconstruction.ply").string(), MeshLoadOptions(), &a).ok());
  ASSERT_TRUE(loadMesh((layered / "reconstruction.ply").string(), MeshLoadOptions(), &b).ok());
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  bool differ = a.vertices.size() != b.vertices.size() || a.triangles.size() != b.triangles.size();
  for (size_t i = 0; !differ && i < a.vertices.size(); ++i) differ = !a.vertices[i].isApprox(b.vertices[i], 1e-6f);
  EXPECT_TRUE(differ);
  EXPECT_DOUBLE_EQ(jsonNumber(json, "mesh_voxel_size_m"), 0.1);
  // A layer of half the voxels: twice as many vertices along each surface,
  // about four times as many in all.
  const fs::path fine = dir_ / "fine";
  const ToolRun f = run(common + " --mesh-voxel-size 0.05 --mesh-truncation 0.15 --out " + fine.string());
  ASSERT_EQ(f.code, 0) << f.out << f.err;
  const std::string fine_json = readText(fine / "refuse.json");
  EXPECT_DOUBLE_EQ(jsonNumber(fine_json, "mesh_voxel_size_m"), 0.05);
  EXPECT_DOUBLE_EQ(jsonNumber(fine_json, "voxel_size_m"), 0.1);
  TriangleMesh c;
  ASSERT_TRUE(loadMesh((fine / "reconstruction.ply").string(), MeshLoadOptions(), &c).ok());
  EXPECT_GT(c.vertices.size(), 3 * a.vertices.size());
}

// nbv_oracle writes its flight timed at the mission's speed and sampled at
// its frame rate (box.yaml: 5 Hz), which nbv_refuse fuses and evaluates as a
// mission's; a lower --cover-fraction flies fewer viewpoints over a shorter
// path and covers less.
TEST_F(NbvRefuse, FusesTheOraclesFlight) {
  ASSERT_TRUE(fs::exists(exe_)) << exe_;
  struct Oracle {
    double path_m, flight_s, viewpoints, covered, coverage;
  };
  auto fly = [&](const std::string& name, const std::string& extra) {
    Oracle o{NAN, NAN, NAN, NAN, NAN};
    const fs::path out = dir_ / name;
    const ToolRun r =
        run("--scene box --config " + config_ + " --threads 1 --out " + out.string() + extra, "nbv_oracle");
    EXPECT_EQ(r.code, 0) << r.out << r.err;
    const std::string json = readText(out / "oracle.json");
    o.path_m = jsonNumber(json, "path_length_m");
    o.flight_s = jsonNumber(json, "flight_time_s");
    o.viewpoints = jsonNumber(json, "viewpoints");
    o.covered = jsonNumber(json, "covered_fraction");
    // The flight file: the header, a frame every 0.2 s from the start pose,
    // the last one at the flight's end.
    std::ifstream csv(out / "oracle_flight.csv");
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "t_s,x_m,y_m,z_m,yaw_rad");
    std::vector<double> t;
    Eigen::Vector3d first = Eigen::Vector3d::Constant(NAN);
    while (std::getline(csv, line)) {
      double v[5];
      EXPECT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4]), 5) << line;
      if (t.empty()) first << v[1], v[2], v[3];
      t.push_back(v[0]);
    }
    EXPECT_GT(t.size(), 10u);
    if (t.size() < 2) return o;
    EXPECT_EQ(t.front(), 0.0);
    EXPECT_TRUE(first.isApprox(Eigen::Vector3d(-5, 0, 2), 1e-9)) << first.transpose();  // box.yaml's start
    for (size_t i = 1; i + 1 < t.size(); ++i) EXPECT_NEAR(t[i] - t[i - 1], 0.2, 1e-9) << "frame " << i;
    EXPECT_GT(t.back() - t[t.size() - 2], 0.0);
    EXPECT_LE(t.back() - t[t.size() - 2], 0.2 + 1e-9);
    EXPECT_NEAR(t.back(), o.flight_s, 1e-6);
    const ToolRun f = run("--scene box --config " + config_ + " --path " + (out / "oracle_flight.csv").string() +
                          " --out " + (out / "refuse").string());
    EXPECT_EQ(f.code, 0) << f.out << f.err;
    o.coverage = jsonNumber(readText(out / "refuse" / "refuse.json"), "coverage");
    return o;
  };
  const Oracle full = fly("full", "");
  const Oracle half = fly("half", " --cover-fraction 0.5");
  // The whole box (measured: 9 viewpoints, 99.08 % of the oracle's targets,
  // 31.5 m) against half of it (3 viewpoints, 59.94 %, 17.6 m).
  EXPECT_GE(full.covered, 0.99);
  EXPECT_GE(half.covered, 0.5);
  EXPECT_LT(half.covered, full.covered);
  EXPECT_LT(half.viewpoints, full.viewpoints);
  EXPECT_LT(half.path_m, full.path_m);
  EXPECT_LT(half.flight_s, full.flight_s);
  // The evaluation's coverage of the fused flights (measured 99.79 % and
  // 62.73 %: the camera sees more than the oracle's strict targets).
  EXPECT_GT(full.coverage, 0.97);
  EXPECT_GT(half.coverage, half.covered - 0.05);
  EXPECT_LT(half.coverage, 0.8);
  const ToolRun bad = run("--scene box --config " + config_ + " --cover-fraction 1.5", "nbv_oracle");
  EXPECT_EQ(bad.code, 2) << bad.out << bad.err;
  EXPECT_NE(bad.err.find("cover_fraction expected in (0, 1]"), std::string::npos) << bad.err;
}

// nbv_mission --coverage-every 20 on the box: a row every 20 s of flight and
// one at the end, in coverage.csv and the reports; the last is the trial's
// coverage, and nbv_refuse on the flight up to a checkpoint gives its figure.
// The reports name the threads, render packets and voxel loop.
TEST_F(NbvRefuse, MissionCoverageOverTime) {
  ASSERT_TRUE(fs::exists(exe_)) << exe_;
  const fs::path out = dir_ / "mission";
  const ToolRun r = run("--scene box --config " + config_ + " --threads 1 --no-plots --coverage-every 20 --out " +
                            out.string(),
                        "nbv_mission");
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  std::ifstream csv(out / "trial_0" / "coverage.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "t_s,path_m,coverage,rmse_m");
  std::vector<std::array<double, 4>> rows;
  while (std::getline(csv, line)) {
    std::array<double, 4> v{};
    EXPECT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3]), 4) << line;
    rows.push_back(v);
  }
  ASSERT_GE(rows.size(), 3u);
  for (size_t k = 0; k + 1 < rows.size(); ++k) {
    EXPECT_GE(rows[k][0], 20.0 * (k + 1) - 1e-6) << k;
    EXPECT_LE(rows[k][0], 20.0 * (k + 1) + 0.2 + 1e-6) << k;
  }
  const std::string json = readText(out / "report.json");
  ASSERT_NE(json.find("\"per_trial\""), std::string::npos) << json;
  const std::string trial = json.substr(json.find("\"per_trial\""));  // past the summary's keys
  EXPECT_NEAR(rows.back()[0], 60.0 * jsonNumber(trial, "completion_min"), 1e-6);
  EXPECT_NEAR(rows.back()[1], jsonNumber(trial, "path_length_m"), 1e-6);
  EXPECT_NEAR(rows.back()[2], jsonNumber(trial, "coverage"), 1e-9);
  EXPECT_LT(rows.front()[2], rows.back()[2]);
  EXPECT_NE(json.find("\"coverage_over_time\": ["), std::string::npos);
  // What the wall time depends on is in the reports: one thread (--threads 1),
  // the renderer's packet width and the voxel loop.
  EXPECT_EQ(jsonNumber(json, "threads"), 1.0);
  const double packet = jsonNumber(json, "render_packet_rays");
  EXPECT_TRUE(packet == 4 || packet == 8 || packet == 16) << packet;
  EXPECT_TRUE(json.find("\"voxel_loop\": \"avx2\"") != std::string::npos ||
              json.find("\"voxel_loop\": \"scalar\"") != std::string::npos)
      << json;
  EXPECT_NE(readText(out / "report.md").find("Compute: 1 thread(s), "), std::string::npos);
  EXPECT_NE(readText(out / "report.md").find("Coverage over flight time"), std::string::npos);
  // The flight up to the second checkpoint, fused again: the same coverage.
  std::ifstream flight(out / "trial_0" / "path.csv");
  std::ostringstream prefix;
  while (std::getline(flight, line)) {
    if (line[0] != 't' && std::strtod(line.c_str(), nullptr) > rows[1][0] + 1e-9) break;
    prefix << line << "\n";
  }
  const std::string prefix_csv = write("prefix.csv", prefix.str());
  const ToolRun f = run("--scene box --config " + config_ + " --path " + prefix_csv + " --out " +
                        (dir_ / "prefix").string());
  EXPECT_EQ(f.code, 0) << f.out << f.err;
  EXPECT_NEAR(jsonNumber(readText(dir_ / "prefix" / "refuse.json"), "coverage"), rows[1][2], 1e-9);
  const ToolRun bad = run("--scene box --config " + config_ + " --coverage-every 0", "nbv_mission");
  EXPECT_EQ(bad.code, 2) << bad.out << bad.err;
  EXPECT_NE(bad.err.find("--coverage-every expects >= 1 s of flight"), std::string::npos) << bad.err;
}

TEST_F(NbvRefuse, RefusesBadInputsNamingThem) {
  ASSERT_TRUE(fs::exists(exe_)) << exe_;
  const std::string head = "t_s,x_m,y_m,z_m,yaw_rad\n0,-5,0,2,0\n";
  const std::string box = "--scene box --config " + config_ + " --out " + (dir_ / "bad").string() + " --path ";
  struct Case {
    std::string arguments, message;
  };
  const std::string bad_number = write("bad_number.csv", head + "0.2,-5,0,abc,0\n");
  const std::string columns = write("columns.csv", head + "0.2,-5,0,2\n");
  const std::string infinite = write("infinite.csv", head + "0.2,-5,0,2,inf\n");
  const std::string blank = write("blank.csv", head + "\n0.4,-5,0,2,0\n");
  const std::string header = write("header.csv", "t,x,y,z,yaw\n0,-5,0,2,0\n");
  const std::string empty = write("empty.csv", "t_s,x_m,y_m,z_m,yaw_rad\n");
  const std::string outside = write("outside.csv", head + "0.2,20,0,2,0\n");
  const std::string good = write("good.csv", head);
  const Case cases[] = {
      {box + bad_number, bad_number + ":3: z_m 'abc' is not a number"},
      {box + columns, columns + ":3: expected 5 comma-separated numbers"},
      {box + infinite, infinite + ":3: yaw_rad 'inf' is not finite"},
      {box + blank, blank + ":3: expected 5 comma-separated numbers"},
      {box + header, header + ":1: expected the header"},
      {box + empty, empty + ": no poses after the header"},
      {box + (dir_ / "missing.csv").string(), "missing.csv' does not exist"},
      {box + dir_.string(), "is not a regular file"},
      {box + outside, outside + ":3: integration of frame 1 (t = 0.2"},
      {box + outside, "camera pose is outside the map bounds"},
      {box + good + " --truncation 0.01", "truncation expected >= voxel_size"},
      {box + good + " --mesh-truncation -1", "mesh_truncation expected 0 (mesh the map itself) or >= the mesh layer's voxel size"},
      {box + good + " --mesh-truncation 0.1 --mesh-voxel-size 0.15", "or >= the mesh layer's voxel size"},
      {box + good + " --mesh-voxel-size -0.1 --mesh-truncation 0.3", "mesh_voxel_size expected >= 0"},
      {box + good + " --mesh-min-weight 1e40", "--mesh-min-weight expects a finite number"},
      {box + good + " --truncation abc", "--truncation expects a number, got 'abc'"},
      {box + good + " --threads 0", "mission/threads expected in [1, 64]"},
      {box + good + " --seed -1", "--seed expects an integer >= 0"},
      {box + good + " --bogus 1", "unknown option --bogus"},
      {"--scene box --config " + config_, "--path PATH.csv is required"},
      {box + good + " --config /nonexistent.yaml", "cannot read '/nonexistent.yaml'"},
  };
  for (const Case& c : cases) {
    const ToolRun r = run(c.arguments);
    EXPECT_EQ(r.code, 2) << c.arguments << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos)
        << c.arguments << "\nexpected: " << c.message << "\ngot: " << r.err;
    EXPECT_EQ(r.err.find("nbv_refuse: "), 0u) << r.err;
  }
}

}  // namespace
