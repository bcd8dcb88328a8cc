// The services of a real tsdf_mapper (mapper_services.test) called in every
// state: before any frame, while mapping, right after a load and right after
// a failed load, each time with good names and with hostile ones ('', '.',
// '..', paths, absolute paths, hidden, too long, control characters, a
// directory, symbolic links to a file outside the directory and to nothing).
// Every call must answer with the documented code (0 done, 1 bad request,
// 2 I/O failure) and a message naming the fault; the map, read back through
// ~save_map, must be exactly as before unless the call was a good load; no
// file may appear outside map_directory; ~request_snapshot must be followed
// by a snapshot on tsdf/update in every state.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <thread>
#include <vector>

#include <std_srvs/Trigger.h>

#include "mapper_probe.h"

using namespace surface_nbv;

namespace {

const std::string kDir = "/tmp/surface_nbv_mapper_services_test";
const std::string kOutside = "/tmp/surface_nbv_mapper_services_outside.map";
const std::string kAbsolute = "/tmp/surface_nbv_mapper_services_absolute.map";
const std::string kEscape = "/tmp/surface_nbv_mapper_services_escape.map";
MapperProbe* probe = nullptr;

bool exists(const std::string& path) {
  struct stat st;
  return lstat(path.c_str(), &st) == 0;
}

// mtime and size of a file, to see that nobody wrote it.
std::pair<long, long> fileStamp(const std::string& path) {
  struct stat st;
  if (stat(path.c_str(), &st) != 0) return {-1, -1};
  return {static_cast<long>(st.st_mtim.tv_sec * 1000000000L + st.st_mtim.tv_nsec), static_cast<long>(st.st_size)};
}

void writeBytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::vector<char> readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Calls a FilePath service and checks its code and that its message holds `fragment`.
void expectCall(const std::string& state, const std::string& service, const std::string& name, int want_code,
                const std::string& fragment) {
  int code = -1;
  std::string message;
  const std::string what = state + ": " + service + " '" + name + "'";
  ASSERT_TRUE(probe->callFile(service, name, &code, &message)) << what << ": the call failed";
  EXPECT_EQ(code, want_code) << what << ": " << message;
  EXPECT_NE(message.find(fragment), std::string::npos) << what << ": message '" << message << "' lacks '" << fragment
                                                       << "'";
}

// ~request_snapshot answers success and a snapshot of `blocks` blocks (any
// number for the maximum size_t) follows on tsdf/update.
void expectSnapshot(const std::string& state, size_t blocks) {
  const uint64_t before = probe->snapshotsReceived();
  std_srvs::Trigger t;
  ASSERT_TRUE(ros::service::call("/tsdf_mapper/request_snapshot", t)) << state;
  EXPECT_TRUE(t.response.success) << state << ": " << t.response.message;
  EXPECT_FALSE(t.response.message.empty()) << state;
  ASSERT_TRUE(MapperProbe::waitUntil([&] { return probe->snapshotsReceived() > before; }, 10.0))
      << state << ": no snapshot on tsdf/update";
  if (blocks != std::numeric_limits<size_t>::max()) {
    EXPECT_EQ(probe->lastUpdate().blocks.size(), blocks) << state;
  }
}

// Every hostile name on every file service: refused as a bad request (code
// 1), the map unchanged and nothing written outside the map directory.
void expectHostileNamesRefused(const std::string& state, const MapDigest& map) {
  struct Case {
    std::string name;
    std::string fragment;
  };
  const std::vector<Case> cases{
      {"", "empty"},
      {".", "may not start with '.'"},
      {"..", "may not start with '.'"},
      {".hidden.map", "may not start with '.'"},
      {"../" + kEscape.substr(5), "may not start with '.'"},
      {"x/../../" + kEscape.substr(5), "is a path"},
      {kAbsolute, "is a path"},
      {"sub/dir.map", "is a path"},
      {"back\\slash.map", "is a path"},
      {std::string(129, 'a'), "longer than 128"},
      {std::string(5000, 'b'), "longer than 128"},
      {"line\nbreak.map", "control characters"},
      {"adir", "not a regular file"},
      {"link.map", "symbolic link"},
      {"dangling.map", "symbolic link"},
  };
  const auto outside = fileStamp(kOutside);
  for (const std::string service : {"save_map", "load_map", "export_mesh"}) {
    for (const Case& c : cases) expectCall(state, service, c.name, 1, c.fragment);
  }
  EXPECT_FALSE(exists(kAbsolute)) << state << ": an absolute name was written";
  EXPECT_FALSE(exists(kEscape)) << state << ": '..' escaped the directory";
  EXPECT_FALSE(exists(kDir + "/sub")) << state;
  EXPECT_EQ(fileStamp(kOutside), outside) << state << ": written through a symbolic link";
  EXPECT_FALSE(exists("/tmp/surface_nbv_mapper_services_nowhere.map")) << state << ": written through a dangling link";
  const MapDigest after = probe->digest();
  EXPECT_EQ(after, map) << state << ": hostile names changed the map";
}

// Fuses `n` frames, each with its transform, and waits for them.
void mapFrames(int n, double x) {
  const uint64_t before = probe->counters()["frames_integrated"];
  for (int k = 0; k < n; ++k) {
    const double t = probe->clock() + 0.5;
    probe->setClock(t);
    probe->publishTf("cam", t, Eigen::Vector3d(x + 0.1 * k, 0.0, 0.5));
    ros::WallDuration(0.1).sleep();
    probe->publishFrame("cam", t);
    ros::WallDuration(0.1).sleep();
  }
  ASSERT_TRUE(MapperProbe::waitUntil([&] { return probe->counters()["frames_integrated"] >= before + n; }, 15.0))
      << "frames not fused";
  ASSERT_TRUE(probe->freshStats(2));
}

}  // namespace

TEST(MapperServices, EveryServiceInEveryStateAnswersAndKeepsTheMap) {
  // No frame fused yet: an empty map saves, loads back and refuses an empty mesh.
  const std::string empty_state = "no frame yet";
  const MapDigest empty = probe->digest();
  ASSERT_TRUE(empty.valid) << empty.error;
  EXPECT_EQ(empty.blocks, 0u);
  expectCall(empty_state, "save_map", "empty.map", 0, "saved 0 blocks");
  expectCall(empty_state, "export_mesh", "empty.ply", 2, "the mesh is empty");
  expectCall(empty_state, "load_map", "missing.map", 1, "no file 'missing.map'");
  expectCall(empty_state, "load_map", "empty.map", 0, "loaded 0 blocks");
  expectSnapshot(empty_state, 0);
  expectHostileNamesRefused(empty_state, empty);

  // Mapping: saves what it holds, exports a mesh, refuses bad loads, keeps the map.
  const std::string mapping = "mapping";
  mapFrames(3, -0.5);
  // While frames stream in, every call answers and every saved map is whole
  // and never smaller than the one before.
  const uint64_t integrated = probe->counters()["frames_integrated"];
  std::atomic<bool> streaming{true};
  std::thread feeder([&] {
    for (int k = 0; k < 10; ++k) {
      const double t = probe->clock() + 0.5;
      probe->setClock(t);
      probe->publishTf("cam", t, Eigen::Vector3d(-1.0 + 0.1 * k, 0.5, 0.5));
      ros::WallDuration(0.1).sleep();
      probe->publishFrame("cam", t);
      ros::WallDuration(0.1).sleep();
    }
    streaming = false;
  });
  size_t saves = 0, previous_blocks = 0;
  while (streaming) {
    expectCall(mapping, "save_map", "streaming.map", 0, "saved");
    const MapDigest d = probe->digestOfFile(kDir + "/streaming.map");
    EXPECT_TRUE(d.valid) << d.error;
    EXPECT_GE(d.blocks, previous_blocks);
    previous_blocks = d.blocks;
    expectCall(mapping, "export_mesh", "streaming.ply", 0, "triangles");
    expectSnapshot(mapping + " (streaming)", std::numeric_limits<size_t>::max());
    ++saves;
  }
  feeder.join();
  EXPECT_GE(saves, 2u);
  EXPECT_TRUE(MapperProbe::waitUntil([&] { return probe->counters()["frames_integrated"] >= integrated + 10; }, 15.0));
  ASSERT_TRUE(probe->freshStats(2));
  const MapDigest mapped = probe->digest();
  ASSERT_TRUE(mapped.valid) << mapped.error;
  ASSERT_GT(mapped.blocks, 0u);
  expectCall(mapping, "save_map", "mapped.map", 0, "saved " + std::to_string(mapped.blocks) + " blocks");
  EXPECT_EQ(probe->digestOfFile(kDir + "/mapped.map"), mapped);
  expectCall(mapping, "export_mesh", "mapped.ply", 0, "triangles to " + kDir + "/mapped.ply");
  EXPECT_GT(readBytes(kDir + "/mapped.ply").size(), 100u);
  expectCall(mapping, "export_mesh", "mapped.obj", 2, "extension expected .ply or .stl");
  expectCall(mapping, "save_map", std::string(128, 'm'), 0, "saved");  // the longest name allowed
  expectCall(mapping, "load_map", "missing.map", 1, "no file");
  expectSnapshot(mapping, mapped.blocks);
  expectHostileNamesRefused(mapping, mapped);

  // Right after a good load: the loaded map replaces the old one, a snapshot
  // follows by itself, every service works and mapping goes on from it.
  const std::string loaded = "after a load";
  uint64_t snapshots = probe->snapshotsReceived();
  expectCall(loaded, "load_map", "empty.map", 0, "loaded 0 blocks");
  EXPECT_EQ(probe->digest(), empty) << "loading the empty map did not empty it";
  EXPECT_TRUE(MapperProbe::waitUntil([&] { return probe->snapshotsReceived() > snapshots; }, 10.0))
      << "no snapshot after a load";
  snapshots = probe->snapshotsReceived();
  expectCall(loaded, "load_map", "mapped.map", 0, "loaded " + std::to_string(mapped.blocks) + " blocks");
  EXPECT_EQ(probe->digest(), mapped) << "the reloaded map differs from the saved one";
  EXPECT_TRUE(MapperProbe::waitUntil([&] { return probe->snapshotsReceived() > snapshots; }, 10.0))
      << "no snapshot after a load";
  EXPECT_EQ(probe->lastUpdate().blocks.size(), mapped.blocks);
  expectCall(loaded, "save_map", "reloaded.map", 0, "saved");
  EXPECT_EQ(probe->digestOfFile(kDir + "/reloaded.map"), mapped);
  expectCall(loaded, "export_mesh", "reloaded.stl", 0, "triangles");
  expectSnapshot(loaded, mapped.blocks);
  expectHostileNamesRefused(loaded, mapped);
  mapFrames(2, 0.5);
  const MapDigest remapped = probe->digest();
  EXPECT_NE(remapped, mapped) << "no mapping after a load";

  // Failed loads of every kind: the map stays exactly as it was.
  const std::string failed = "after a failed load";
  const std::vector<char> good = readBytes(kDir + "/mapped.map");
  ASSERT_GT(good.size(), 200u);
  writeBytes(kDir + "/garbage.map", std::vector<char>(1000, 'x'));
  writeBytes(kDir + "/truncated.map", std::vector<char>(good.begin(), good.begin() + good.size() / 2));
  std::vector<char> flipped = good;
  flipped[good.size() / 2] ^= 0x40;
  writeBytes(kDir + "/flipped.map", flipped);
  writeBytes(kDir + "/zero.map", {});
  TsdfConfig coarse_config = probe->mapConfig();
  coarse_config.voxel_size *= 2.0;
  TsdfMap coarse(coarse_config);
  coarse.allocateBlock(Eigen::Vector3i(1, 1, 1));
  ASSERT_TRUE(saveMap(coarse, kDir + "/coarse.map").ok());
  const std::vector<std::pair<std::string, std::string>> bad_files{
      {"garbage.map", "no \"SNBVTSDF\" magic"}, {"truncated.map", "truncated"},
      {"flipped.map", "checksum mismatch"},     {"zero.map", "no \"SNBVTSDF\" magic"},
      {"coarse.map", "voxel size"},
  };
  for (const auto& [name, fragment] : bad_files) {
    expectCall(failed, "load_map", name, 2, fragment);
    EXPECT_EQ(probe->digest(), remapped) << failed << " (" << name << "): the map changed";
  }
  expectCall(failed, "save_map", "after_failed.map", 0, "saved " + std::to_string(remapped.blocks) + " blocks");
  EXPECT_EQ(probe->digestOfFile(kDir + "/after_failed.map"), remapped);
  expectCall(failed, "export_mesh", "after_failed.ply", 0, "triangles");
  expectSnapshot(failed, remapped.blocks);
  expectHostileNamesRefused(failed, remapped);
  mapFrames(2, 1.0);
  EXPECT_NE(probe->digest(), remapped) << "no mapping after a failed load";
  // A load that fails leaves the files it read untouched.
  EXPECT_EQ(readBytes(kDir + "/flipped.map"), flipped);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_mapper_services");
  // A clean directory with a subdirectory and two symbolic links: one to a
  // valid map outside it, one to nothing.
  std::system(("rm -rf " + kDir + " " + kOutside + " " + kAbsolute + " " + kEscape).c_str());
  std::system(("mkdir -p " + kDir + "/adir").c_str());
  MapperTestNode node(kDir, "/tsdf_mapper");
  if (!node.ok) return 1;
  MapperProbe& p = node.probe;
  TsdfMap outside(p.mapConfig());
  outside.allocateBlock(Eigen::Vector3i(2, 2, 2));
  if (!saveMap(outside, kOutside).ok() || symlink(kOutside.c_str(), (kDir + "/link.map").c_str()) != 0 ||
      symlink("/tmp/surface_nbv_mapper_services_nowhere.map", (kDir + "/dangling.map").c_str()) != 0) {
    std::fprintf(stderr, "cannot prepare %s\n", kDir.c_str());
    return 1;
  }
  probe = &p;
  return RUN_ALL_TESTS();
}
