// libFuzzer target: map files (map/map_io.h) through loadMap. Byte 0 is a
// flag: when odd, the CRC-32 at the end of the file is recomputed over the
// rest, so that mutations get past the checksum and reach the header, block
// and voxel checks. The map loaded into holds seeded blocks first; a refused
// file must leave it exactly as it was, an accepted one must leave it sound.
#include <zlib.h>

#include <random>
#include <vector>

#include "../test/fuzz/map_digest.h"
#include "fuzz_support.h"
#include "surface_nbv/map/map_io.h"

using namespace surface_nbv;
using namespace surface_nbv::fuzz;

namespace {

// The configuration the seeds were saved with (make_seeds.cpp).
TsdfConfig fileConfig() {
  TsdfConfig config;
  config.voxel_size = 0.25;
  config.bounds = AlignedBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(8, 8, 4));
  config.max_blocks = 24;
  return config;
}

void prefill(TsdfMap* map) {
  std::mt19937 rng(7);
  for (int b = 0; b < 3; ++b) {
    TsdfBlock* block = map->allocateBlock(Eigen::Vector3i(b, 1, 0));
    for (TsdfVoxel& v : block->voxels) {
      v.phi = std::uniform_real_distribution<float>(-0.5f, 0.5f)(rng);
      v.w = 1.0f;
    }
    block->change_stamp = map->beginChange();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::vector<uint8_t> file(data + 1, data + size);
  if ((data[0] & 1) != 0 && file.size() >= 4) {
    const uint32_t crc = static_cast<uint32_t>(crc32(0, file.data(), static_cast<uInt>(file.size() - 4)));
    for (int i = 0; i < 4; ++i) file[file.size() - 4 + i] = static_cast<uint8_t>(crc >> (8 * i));
  }
  static MemoryFile memory;
  const std::string& path = memory.write(file.data(), file.size());
  TsdfMap map(fileConfig());
  prefill(&map);
  const uint64_t before = mapDigest(map);
  const Status s = loadMap(path, &map);
  if (!s) {
    FUZZ_CHECK(!s.message().empty(), "a refusal without a reason");
    FUZZ_CHECK(mapDigest(map) == before, "a refused map file changed the map: " + s.message());
    return 0;
  }
  FUZZ_CHECK(mapFault(map).empty(), mapFault(map));
  FUZZ_CHECK(map.changeCounter() > 3 || map.numBlocks() == 0, "loaded blocks carry no fresh stamp");
  return 0;
}
