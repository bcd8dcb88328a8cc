// Writes the seed corpus of the libFuzzer targets into DIR/<target>/ (usage:
// make_seeds DIR). Every seed is a valid input made by the package's own
// writers (saveMap, toUpdateMsg and ros::serialization) or by the fuzz tests'
// seed builders, from fixed seeds, so the output is the same on every run.
#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <ros/serialization.h>

#include "../test/fuzz/message_cases.h"
#include "depth_input.h"
#include "surface_nbv/map/map_io.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/map_conversions.h"

using namespace surface_nbv;
using namespace surface_nbv::fuzz;

namespace {

bool writeSeed(const std::string& dir, const std::string& name, const std::vector<uint8_t>& bytes) {
  ::mkdir(dir.c_str(), 0755);
  std::ofstream out(dir + "/" + name, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(out);
}

std::vector<uint8_t> readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<uint8_t> serialise(const surface_nbv::TsdfUpdate& msg) {
  std::vector<uint8_t> bytes(ros::serialization::serializationLength(msg));
  ros::serialization::OStream stream(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::serialize(stream, msg);
  return bytes;
}

std::vector<uint8_t> text(const std::string& s) { return std::vector<uint8_t>(s.begin(), s.end()); }

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_seeds DIR\n");
    return 2;
  }
  const std::string root = argv[1];
  ::mkdir(root.c_str(), 0755);
  bool ok = true;
  Mutator m(20240909);

  const std::string depth = root + "/depth_conversions";
  for (int i = 0; i < 4; ++i) {
    ok &= writeSeed(depth, "image_" + std::to_string(i), encodeImage(seedImage(m)));
    ok &= writeSeed(depth, "cloud_" + std::to_string(i), encodeCloud(seedCloud(m)));
    ok &= writeSeed(depth, "camera_info_" + std::to_string(i), encodeCameraInfo(seedCameraInfo(m)));
  }

  // The map files carry a leading flag byte: 1 = recompute the CRC (fuzz_map_file.cpp).
  const std::string maps = root + "/map_file";
  TsdfMap map(fuzzMapConfig());
  for (int blocks : {0, 1, 3}) {
    scribbleMap(&map, blocks, m);
    const std::string tmp = root + "/.seed_map.bin";
    if (!saveMap(map, tmp)) return 1;
    std::vector<uint8_t> bytes(1, 1);
    const std::vector<uint8_t> file = readAll(tmp);
    bytes.insert(bytes.end(), file.begin(), file.end());
    std::remove(tmp.c_str());
    ok &= writeSeed(maps, "map_" + std::to_string(map.numBlocks()) + "_blocks", bytes);
  }

  // Updates for a mirror at sequence 1: the next incremental one, a later
  // snapshot, and an empty incremental one.
  const std::string updates = root + "/tsdf_update";
  TsdfMap publisher(fuzzMapConfig());
  scribbleMap(&publisher, 3, m);
  const uint64_t since = publisher.changeCounter();
  scribbleMap(&publisher, 2, m);
  MapUpdate u;
  std_msgs::Header header;
  header.frame_id = "world";
  for (const std::string name : {"incremental_2", "snapshot_5", "empty_2"}) {
    if (name == "incremental_2") makeUpdate(publisher, since, 2, false, &u);
    if (name == "snapshot_5") makeUpdate(publisher, 0, 5, true, &u);
    if (name == "empty_2") makeUpdate(publisher, publisher.changeCounter(), 2, false, &u);
    surface_nbv::TsdfUpdate msg;
    toUpdateMsg(u, header, &msg);
    ok &= writeSeed(updates, name, serialise(msg));
  }

  const std::string tsplib = root + "/tsplib";
  ok &= writeSeed(tsplib, "atsp_explicit.atsp",
                  text("NAME: a3\nTYPE: ATSP\nDIMENSION: 3\nEDGE_WEIGHT_TYPE: EXPLICIT\n"
                       "EDGE_WEIGHT_FORMAT: FULL_MATRIX\nEDGE_WEIGHT_SECTION\n0 1 2\n3 0 4\n5 6 0\nEOF\n"));
  ok &= writeSeed(tsplib, "tsp_euc2d.tsp",
                  text("NAME: e4\nCOMMENT: a square\nTYPE: TSP\nDIMENSION: 4\nEDGE_WEIGHT_TYPE: EUC_2D\n"
                       "NODE_COORD_SECTION\n1 0 0\n2 10 0\n3 10 10\n4 0 10.5\nEOF\n"));
  ok &= writeSeed(tsplib, "tsp_explicit.tsp",
                  text("NAME: s2\nTYPE: TSP\nDIMENSION: 2\nEDGE_WEIGHT_TYPE: EXPLICIT\n"
                       "EDGE_WEIGHT_FORMAT: FULL_MATRIX\nEDGE_WEIGHT_SECTION\n0 7.5\n7.5 0\n"));
  if (!ok) {
    std::fprintf(stderr, "make_seeds: cannot write under %s\n", root.c_str());
    return 1;
  }
  return 0;
}
