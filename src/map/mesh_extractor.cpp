#include "surface_nbv/map/mesh_extractor.h"

#include <array>
#include <unordered_map>
#include <utility>


namespace surface_nbv {
namespace {

// Cube corners (Bourke's numbering) and the corners each of the 12 edges joins.
constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
constexpr int kEdgeCorners[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                     {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

// The classical tables (Lorensen-Cline, as tabulated by Bourke). Bit i of a
// configuration is set when corner i has phi < 0; kEdgeTable lists the edges
// the surface crosses.
constexpr uint16_t kEdgeTable[256] = {
    0x000, 0x109, 0x203, 0x30a, 0x406, 0x50f, 0x605, 0x70c,
    0x80c, 0x905, 0xa0f, 0xb06, 0xc0a, 0xd03, 0xe09, 0xf00,
    0x190, 0x099, 0x393, 0x29a, 0x596, 0x49f, 0x795, 0x69c,
    0x99c, 0x895, 0xb9f, 0xa96, 0xd9a, 0xc93, 0xf99, 0xe90,
    0x230, 0x339, 0x033, 0x13a, 0x636, 0x73f, 0x435, 0x53c,
    0xa3c, 0xb35, 0x83f, 0x936, 0xe3a, 0xf33, 0xc39, 0xd30,
    0x3a0, 0x2a9, 0x1a3, 0x0aa, 0x7a6, 0x6af, 0x5a5, 0x4ac,
    0xbac, 0xaa5, 0x9af, 0x8a6, 0xfaa, 0xea3, 0xda9, 0xca0,
    0x460, 0x569, 0x663, 0x76a, 0x066, 0x16f, 0x265, 0x36c,
    0xc6c, 0xd65, 0xe6f, 0xf66, 0x86a, 0x963, 0xa69, 0xb60,
    0x5f0, 0x4f9, 0x7f3, 0x6fa, 0x1f6, 0x0ff, 0x3f5, 0x2fc,
    0xdfc, 0xcf5, 0xfff, 0xef6, 0x9fa, 0x8f3, 0xbf9, 0xaf0,
    0x650, 0x759, 0x453, 0x55a, 0x256, 0x35f, 0x055, 0x15c,
    0xe5c, 0xf55, 0xc5f, 0xd56, 0xa5a, 0xb53, 0x859, 0x950,
    0x7c0, 0x6c9, 0x5c3, 0x4ca, 0x3c6, 0x2cf, 0x1c5, 0x0cc,
    0xfcc, 0xec5, 0xdcf, 0xcc6, 0xbca, 0xac3, 0x9c9, 0x8c0,
    0x8c0, 0x9c9, 0xac3, 0xbca, 0xcc6, 0xdcf, 0xec5, 0xfcc,
    0x0cc, 0x1c5, 0x2cf, 0x3c6, 0x4ca, 0x5c3, 0x6c9, 0x7c0,
    0x950, 0x859, 0xb53, 0xa5a, 0xd56, 0xc5f, 0xf55, 0xe5c,
    0x15c, 0x055, 0x35f, 0x256, 0x55a, 0x453, 0x759, 0x650,
    0xaf0, 0xbf9, 0x8f3, 0x9fa, 0xef6, 0xfff, 0xcf5, 0xdfc,
    0x2fc, 0x3f5, 0x0ff, 0x1f6, 0x6fa, 0x7f3, 0x4f9, 0x5f0,
    0xb60, 0xa69, 0x963, 0x86a, 0xf66, 0xe6f, 0xd65, 0xc6c,
    0x36c, 0x265, 0x16f, 0x066, 0x76a, 0x663, 0x569, 0x460,
    0xca0, 0xda9, 0xea3, 0xfaa, 0x8a6, 0x9af, 0xaa5, 0xbac,
    0x4ac, 0x5a5, 0x6af, 0x7a6, 0x0aa, 0x1a3, 0x2a9, 0x3a0,
    0xd30, 0xc39, 0xf33, 0xe3a, 0x936, 0x83f, 0xb35, 0xa3c,
    0x53c, 0x435, 0x73f, 0x636, 0x13a, 0x033, 0x339, 0x230,
    0xe90, 0xf99, 0xc93, 0xd9a, 0xa96, 0xb9f, 0x895, 0x99c,
    0x69c, 0x795, 0x49f, 0x596, 0x29a, 0x393, 0x099, 0x190,
    0xf00, 0xe09, 0xd03, 0xc0a, 0xb06, 0xa0f, 0x905, 0x80c,
    0x70c, 0x605, 0x50f, 0x406, 0x30a, 0x203, 0x109, 0x000,
};
// Triangles per cube configuration, three hex edge numbers each.
constexpr const char* kTriTable[256] = {
    "", "083", "019", "183 981",
    "12a", "083 12a", "92a 029", "283 2a8 a98",
    "3b2", "0b2 8b0", "190 23b", "1b2 19b 98b",
    "3a1 ba3", "0a1 08a 8ba", "390 3b9 ba9", "98a a8b",
    "478", "430 734", "019 847", "419 471 731",
    "12a 847", "347 304 12a", "92a 902 847", "2a9 297 273 794",
    "847 3b2", "b47 b24 204", "901 847 23b", "47b 94b 9b2 921",
    "3a1 3ba 784", "1ba 14b 104 7b4", "478 90b 9ba b03", "47b 4b9 9ba",
    "954", "954 083", "054 150", "854 835 315",
    "12a 954", "308 12a 495", "52a 542 402", "2a5 325 354 348",
    "954 23b", "0b2 08b 495", "054 015 23b", "215 258 28b 485",
    "a3b a13 954", "495 081 8a1 8ba", "540 50b 5ba b03", "548 58a a8b",
    "978 579", "930 953 573", "078 017 157", "153 357",
    "978 957 a12", "a12 950 530 573", "802 825 857 a52", "2a5 253 357",
    "795 789 3b2", "957 972 920 27b", "23b 018 178 157", "b21 b17 715",
    "958 857 a13 a3b", "570 509 7b0 10a ba0", "ba0 b03 a50 807 570", "ba5 7b5",
    "a65", "083 5a6", "901 5a6", "183 198 5a6",
    "165 261", "165 126 308", "965 906 026", "598 582 526 328",
    "23b a65", "b08 b20 a65", "019 23b 5a6", "5a6 192 9b2 98b",
    "63b 653 513", "08b 0b5 051 5b6", "3b6 036 065 059", "659 69b b98",
    "5a6 478", "430 473 65a", "190 5a6 847", "a65 197 173 794",
    "612 651 478", "125 526 304 347", "847 905 065 026", "739 794 329 596 269",
    "3b2 784 a65", "5a6 472 420 27b", "019 478 23b 5a6", "921 9b2 94b 7b4 5a6",
    "847 3b5 351 5b6", "51b 5b6 10b 7b4 04b", "059 065 036 b63 847", "659 69b 479 7b9",
    "a49 64a", "4a6 49a 083", "a01 a60 640", "831 816 864 61a",
    "149 124 264", "308 129 249 264", "024 426", "832 824 426",
    "a49 a64 b23", "082 28b 49a 4a6", "3b2 016 064 61a", "641 61a 481 21b 8b1",
    "964 936 913 b63", "8b1 810 b61 914 641", "3b6 360 064", "648 b68",
    "7a6 78a 89a", "073 0a7 09a 67a", "a67 1a7 178 180", "a67 a71 173",
    "126 168 189 867", "269 291 679 093 739", "780 706 602", "732 672",
    "23b a68 a89 867", "207 27b 097 67a 9a7", "180 178 1a7 67a 23b", "b21 b17 a61 671",
    "896 867 916 b63 136", "091 b67", "780 706 3b0 b60", "7b6",
    "76b", "308 b76", "019 b76", "819 831 b76",
    "a12 6b7", "12a 308 6b7", "290 2a9 6b7", "6b7 2a3 a83 a98",
    "723 627", "708 760 620", "276 237 019", "162 186 198 876",
    "a76 a17 137", "a76 17a 187 108", "037 07a 0a9 6a7", "76a 7a8 8a9",
    "684 b86", "36b 306 046", "86b 846 901", "946 963 931 b36",
    "684 6b8 2a1", "12a 30b 06b 046", "4b8 46b 029 2a9", "a93 a32 943 b36 463",
    "823 842 462", "042 462", "190 234 246 438", "194 142 246",
    "813 861 846 6a1", "a10 a06 604", "463 438 6a3 039 a93", "a94 6a4",
    "495 76b", "083 495 b76", "501 540 76b", "b76 834 354 315",
    "954 a12 76b", "6b7 12a 083 495", "76b 54a 42a 402", "348 354 325 a52 b76",
    "723 762 549", "954 086 062 687", "362 376 150 540", "628 687 218 485 158",
    "954 a16 176 137", "16a 176 107 870 954", "40a 4a5 03a 6a7 37a", "76a 7a8 54a 48a",
    "695 6b9 b89", "36b 063 056 095", "0b8 05b 015 56b", "6b3 635 531",
    "12a 95b 9b8 b56", "0b3 06b 096 569 12a", "b85 b56 805 a52 025", "6b3 635 2a3 a53",
    "589 528 562 382", "956 960 062", "158 180 568 382 628", "156 216",
    "136 16a 386 569 896", "a10 a06 950 560", "038 56a", "a56",
    "b5a 75b", "b5a b75 830", "5b7 5ab 190", "a75 ab7 981 831",
    "b12 b71 751", "083 127 175 72b", "975 927 902 2b7", "752 72b 592 328 982",
    "25a 235 375", "820 852 875 a25", "901 5a3 537 3a2", "982 921 872 a25 752",
    "135 375", "087 071 175", "903 935 537", "987 597",
    "584 5a8 ab8", "504 5b0 5ab b30", "019 84a 8ab a45", "ab4 a45 b34 941 314",
    "251 285 2b8 458", "04b 0b3 45b 2b1 51b", "025 059 2b5 458 b85", "945 2b3",
    "25a 352 345 384", "5a2 524 420", "3a2 35a 385 458 019", "5a2 524 192 942",
    "845 853 351", "045 105", "845 853 905 035", "945",
    "4b7 49b 9ab", "083 497 9b7 9ab", "1ab 1b4 140 74b", "314 348 1a4 74b ab4",
    "4b7 9b4 92b 912", "974 9b7 91b 2b1 083", "b74 b42 240", "b74 b42 834 324",
    "29a 279 237 749", "9a7 974 a27 870 207", "37a 3a2 74a 1a0 40a", "1a2 874",
    "491 417 713", "491 417 081 871", "403 743", "487",
    "9a8 ab8", "309 39b b9a", "01a 0a8 8ab", "31a b3a",
    "12b 1b9 9b8", "309 39b 129 2b9", "02b 80b", "32b",
    "238 28a a89", "9a2 092", "238 28a 018 1a8", "1a2",
    "138 918", "091", "038", "",
};

// kTriTable decoded once: up to 5 triangles of edge numbers, -1 terminated.
struct TriangleTable {
  std::array<std::array<int8_t, 16>, 256> edges;

  TriangleTable() {
    for (int cube = 0; cube < 256; ++cube) {
      edges[cube].fill(-1);
      int n = 0;
      for (const char* c = kTriTable[cube]; *c != '\0'; ++c) {
        if (*c != ' ') edges[cube][n++] = static_cast<int8_t>(*c <= '9' ? *c - '0' : *c - 'a' + 10);
      }
    }
  }
};

const TriangleTable& triangleTable() {
  static const TriangleTable table;
  return table;
}

constexpr int kPad = kBlockSize + 1;  // a block's samples plus one layer of its upper neighbours

int padIndex(int x, int y, int z) { return x + kPad * (y + kPad * z); }

}  // namespace

BlockMesh MeshExtractor::meshBlock(const TsdfMap& map, const Eigen::Vector3i& block) {
  BlockMesh out;
  out.block = block;
  // Meshed voxels: w >= w_th, or w > mesh_min_weight when that is set (>= 0).
  const float mesh_min = map.config().mesh_min_weight;
  const bool use_w_th = mesh_min < 0.0f;
  const float w_th = map.config().w_th;
  std::array<float, kPad * kPad * kPad> phi;
  std::array<uint8_t, kPad * kPad * kPad> known;
  known.fill(0);
  for (int oz = 0; oz < 2; ++oz) {
    for (int oy = 0; oy < 2; ++oy) {
      for (int ox = 0; ox < 2; ++ox) {
        const TsdfBlock* source = map.block(block + Eigen::Vector3i(ox, oy, oz));
        if (source == nullptr) continue;
        const int n[3] = {ox ? 1 : kBlockSize, oy ? 1 : kBlockSize, oz ? 1 : kBlockSize};
        for (int z = 0; z < n[2]; ++z) {
          for (int y = 0; y < n[1]; ++y) {
            for (int x = 0; x < n[0]; ++x) {
              const TsdfVoxel& v = source->at(x, y, z);
              const int p = padIndex(x + ox * kBlockSize, y + oy * kBlockSize, z + oz * kBlockSize);
              phi[p] = v.phi;
              known[p] = use_w_th ? v.w >= w_th : v.w > mesh_min;
            }
          }
        }
      }
    }
  }

  const double voxel = map.voxelSize();
  const Eigen::Vector3i first_voxel = block * kBlockSize;
  const Eigen::Vector3d first_center = map.voxelCenter(first_voxel);
  const Eigen::Vector3i lattice = map.gridBlocks() * kBlockSize + Eigen::Vector3i::Ones();
  const TriangleTable& table = triangleTable();
  std::array<int32_t, kPad * kPad * kPad * 3> edge_vertex;
  edge_vertex.fill(-1);

  for (int z = 0; z < kBlockSize; ++z) {
    for (int y = 0; y < kBlockSize; ++y) {
      for (int x = 0; x < kBlockSize; ++x) {
        float c[8];
        int cube = 0;
        bool all_known = true;
        for (int i = 0; i < 8 && all_known; ++i) {
          const int p = padIndex(x + kCorner[i][0], y + kCorner[i][1], z + kCorner[i][2]);
          all_known = known[p] != 0;
          c[i] = all_known ? phi[p] : 0.0f;
          if (c[i] < 0.0f) cube |= 1 << i;
        }
        if (!all_known || cube == 0 || cube == 255) continue;
        int vertex[12];
        for (int e = 0; e < 12; ++e) {
          if ((kEdgeTable[cube] & (1 << e)) == 0) continue;
          int lo = kEdgeCorners[e][0], hi = kEdgeCorners[e][1];
          const int axis = kCorner[lo][0] != kCorner[hi][0] ? 0 : kCorner[lo][1] != kCorner[hi][1] ? 1 : 2;
          if (kCorner[lo][axis] > kCorner[hi][axis]) std::swap(lo, hi);
          const Eigen::Vector3i l(x + kCorner[lo][0], y + kCorner[lo][1], z + kCorner[lo][2]);
          int32_t& slot = edge_vertex[padIndex(l.x(), l.y(), l.z()) * 3 + axis];
          if (slot < 0) {
            const double t = static_cast<double>(c[lo]) / (static_cast<double>(c[lo]) - static_cast<double>(c[hi]));
            Eigen::Vector3d p = first_center + voxel * l.cast<double>();
            p[axis] += t * voxel;
            const Eigen::Vector3i g = first_voxel + l;
            slot = static_cast<int32_t>(out.mesh.vertices.size());
            out.mesh.vertices.push_back(p.cast<float>());
            out.edge_keys.push_back(
                ((static_cast<uint64_t>(g.z()) * lattice.y() + g.y()) * lattice.x() + g.x()) * 3 + axis);
          }
          vertex[e] = slot;
        }
        const std::array<int8_t, 16>& tri = table.edges[cube];
        for (int k = 0; k < 16 && tri[k] >= 0; k += 3) {
          // The table winds triangles facing negative phi; reverse them.
          out.mesh.triangles.emplace_back(vertex[tri[k]], vertex[tri[k + 2]], vertex[tri[k + 1]]);
        }
      }
    }
  }
  return out;
}

size_t MeshExtractor::update(const TsdfMap& map) {
  updated_.clear();
  const uint64_t counter = map.changeCounter();
  if (counter < last_counter_ || map.gridBlocks() != grid_blocks_) full_ = true;
  std::set<Eigen::Vector3i, BlockIndexLess> dirty;
  const auto touch = [&](const Eigen::Vector3i& b) {
    for (int d = 0; d < 8; ++d) {
      const Eigen::Vector3i reader = b - Eigen::Vector3i(d & 1, (d >> 1) & 1, (d >> 2) & 1);
      if (map.blockInBounds(reader)) dirty.insert(reader);
    }
  };
  if (full_) {
    for (const auto& entry : meshes_) dirty.insert(entry.first);
    seen_.clear();
    for (const auto& b : map.blocks()) {
      dirty.insert(b->index);
      seen_.insert(b->index);
    }
  } else {
    for (auto it = seen_.begin(); it != seen_.end();) {
      if (map.block(*it) != nullptr) {
        ++it;
        continue;
      }
      touch(*it);
      it = seen_.erase(it);
    }
    for (const auto& b : map.blocks()) {
      if (b->change_stamp <= last_counter_) continue;
      touch(b->index);
      seen_.insert(b->index);
    }
  }
  for (const Eigen::Vector3i& b : dirty) {
    if (map.block(b) == nullptr) {
      if (meshes_.erase(b) > 0) updated_.push_back(b);
      continue;
    }
    BlockMesh m = meshBlock(map, b);
    if (m.mesh.empty()) meshes_.erase(b);
    else meshes_[b] = std::move(m);
    updated_.push_back(b);
  }
  last_counter_ = counter;
  grid_blocks_ = map.gridBlocks();
  full_ = false;
  return updated_.size();
}

void MeshExtractor::reset() {
  meshes_.clear();
  seen_.clear();
  updated_.clear();
  last_counter_ = 0;
  full_ = true;
}

TriangleMesh MeshExtractor::mesh(bool merge_vertices) const {
  TriangleMesh out;
  if (!merge_vertices) {
    for (const auto& entry : meshes_) out.append(entry.second.mesh);
    return out;
  }
  std::unordered_map<uint64_t, int> merged;
  std::vector<int> remap;
  for (const auto& entry : meshes_) {
    const BlockMesh& bm = entry.second;
    remap.resize(bm.mesh.vertices.size());
    for (size_t i = 0; i < remap.size(); ++i) {
      const auto inserted = merged.emplace(bm.edge_keys[i], static_cast<int>(out.vertices.size()));
      if (inserted.second) out.vertices.push_back(bm.mesh.vertices[i]);
      remap[i] = inserted.first->second;
    }
    for (const Eigen::Vector3i& t : bm.mesh.triangles) out.triangles.emplace_back(remap[t[0]], remap[t[1]], remap[t[2]]);
  }
  return out;
}


}  // namespace surface_nbv
