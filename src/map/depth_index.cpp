#include "surface_nbv/map/depth_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "surface_nbv/util/parallel_for.h"
#include "surface_nbv/util/simd.h"

namespace surface_nbv {
namespace {

constexpr int kTile = 8;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kNone = -kInf;
// The silhouette key of a pixel without usable depth: far beyond any depth,
// finite, so two such pixels compare equal.
constexpr float kFar = 1e30f;

// One image row: usable depth (+inf clears, NaN carries nothing), the
// silhouette key, the farthest reach (max range for clearing pixels, kNone for
// none) folded into the column maxima of the row's band of tiles, the nearest
// measured depth into the column minima when given, and the number of invalid
// pixels. Branch-free, so it is vectorised: for AVX2 too where the CPU has it
// (compares, max and min only, so both versions give the same bits).
SURFACE_NBV_AVX2_CLONES int prepareRow(const float* in, float lo, float hi, bool clear_all, bool clear_inf,
                                       int width, float* out, float* key, float* col_max, float* col_min) {
  int bad = 0;
  for (int u = 0; u < width; ++u) {
    const float d = in[u];
    const bool ok = (d >= lo) & (d <= hi);  // false for NaN
    const bool clears = (!ok) & (clear_all | (clear_inf & (d > hi)));
    const float none = clears ? kInf : kNaN;
    out[u] = ok ? d : none;
    key[u] = ok ? d : kFar;
    const float reach = ok ? d : (clears ? hi : kNone);
    col_max[u] = std::max(col_max[u], reach);
    bad += ok ? 0 : 1;
  }
  if (col_min != nullptr) {
    for (int u = 0; u < width; ++u) col_min[u] = std::min(col_min[u], out[u]);  // std::min keeps col_min for a NaN
  }
  return bad;
}

// One row of silhouette flags: |key - a 4-neighbour's key| > t, the image
// border comparing a pixel with itself. Subtractions, abs and max only.
SURFACE_NBV_AVX2_CLONES void silhouetteRow(const float* __restrict k, const float* __restrict up,
                                           const float* __restrict down, float t, int width,
                                           uint8_t* __restrict s) {
  const auto differs = [&](int u, int left, int right) {
    const float c = k[u];
    const float m = std::max(std::max(std::abs(c - k[left]), std::abs(c - k[right])),
                             std::max(std::abs(c - up[u]), std::abs(c - down[u])));
    return static_cast<uint8_t>(m > t);
  };
  for (int u = 1; u < width - 1; ++u) s[u] = differs(u, u - 1, u + 1);  // vectorised: no index choices inside
  s[0] = differs(0, 0, std::min(1, width - 1));
  if (width > 1) s[width - 1] = differs(width - 1, width - 2, width - 1);
}

}  // namespace

size_t DepthIndex::build(const DepthCamera& camera, const DepthImage& depth, float truncation,
                         InvalidPixelPolicy policy, int threads, bool nearest) {
  const int W = depth.width, H = depth.height;
  const float min_range = static_cast<float>(camera.config().min_range);
  const float max_range = static_cast<float>(camera.config().max_range);
  const bool clear_all = policy == InvalidPixelPolicy::kClearToMaxRange;
  const bool clear_inf = policy == InvalidPixelPolicy::kClearInfinite;
  const size_t n = depth.data.size();
  usable_.resize(n);
  key_.resize(n);
  silhouette_.resize(n);
  if (levels_.empty()) levels_.resize(1);
  Level& base = levels_[0];
  base.width = (W + kTile - 1) / kTile;
  base.height = (H + kTile - 1) / kTile;
  base.max_depth.assign(static_cast<size_t>(base.width) * base.height, kNone);
  if (nearest) {
    base.min_depth.assign(static_cast<size_t>(base.width) * base.height, kInf);
  } else {
    base.min_depth.clear();
  }

  // Pass 1, by bands of tile rows: usable depth, the silhouette key, the
  // farthest reach of each pixel (max range for cleared ones), tile maxima
  // and the invalid count. The per-pixel loops have no branches.
  std::vector<size_t> invalid(static_cast<size_t>(base.height), 0);
  parallelFor(static_cast<size_t>(base.height), threads, [&](size_t ty) {
    // Local copies: the loops store floats and bytes, which could alias captured references.
    const float lo = min_range, hi = max_range;
    const bool all = clear_all, infinite = clear_inf;
    const int width = W;
    const int v_end = std::min(H, static_cast<int>(ty + 1) * kTile);
    float* tile_max = &base.max_depth[ty * base.width];
    float* tile_min = nearest ? &base.min_depth[ty * base.width] : nullptr;
    // Column maxima (and minima) over the band's rows, then one pass over
    // the tiles: the same maxima and minima as pixel by pixel.
    std::vector<float> col_max(static_cast<size_t>(W), kNone);
    std::vector<float> col_min(nearest ? static_cast<size_t>(W) : 0, kInf);
    for (int v = static_cast<int>(ty) * kTile; v < v_end; ++v) {
      const size_t row = static_cast<size_t>(v) * W;
      invalid[ty] += static_cast<size_t>(prepareRow(&depth.data[row], lo, hi, all, infinite, width, &usable_[row],
                                                    &key_[row], col_max.data(),
                                                    nearest ? col_min.data() : nullptr));
    }
    for (int u0 = 0, tx = 0; u0 < width; u0 += kTile, ++tx) {
      const int u1 = std::min(width, u0 + kTile);
      float m = tile_max[tx];
      for (int u = u0; u < u1; ++u) m = std::max(m, col_max[u]);
      tile_max[tx] = m;
      if (tile_min == nullptr) continue;
      float near = tile_min[tx];
      for (int u = u0; u < u1; ++u) near = std::min(near, col_min[u]);
      tile_min[tx] = near;
    }
  });
  // Pass 2: a pixel is on a silhouette when it differs from one of its four
  // neighbours: one has a usable depth and the other not, or both have and
  // are further apart than the truncation. With every pixel without usable
  // depth keyed kFar, both cases are |key - neighbour's key| > truncation.
  // Each row is written by one task only.
  parallelFor(static_cast<size_t>(H), threads, [&](size_t r) {
    const int v = static_cast<int>(r);
    const float* k = &key_[static_cast<size_t>(v) * W];
    const float* up = v > 0 ? k - W : k;  // the image border compares a pixel with itself
    const float* down = v + 1 < H ? k + W : k;
    silhouetteRow(k, up, down, truncation, W, &silhouette_[static_cast<size_t>(v) * W]);
  });
  // Pyramids: each level halves the previous one with max (and min).
  size_t k = 1;
  for (; levels_[k - 1].width > 1 || levels_[k - 1].height > 1; ++k) {
    if (levels_.size() <= k) levels_.emplace_back();
    const Level& fine = levels_[k - 1];
    Level& coarse = levels_[k];
    coarse.width = (fine.width + 1) / 2;
    coarse.height = (fine.height + 1) / 2;
    coarse.max_depth.assign(static_cast<size_t>(coarse.width) * coarse.height, kNone);
    coarse.min_depth.assign(nearest ? static_cast<size_t>(coarse.width) * coarse.height : 0, kInf);
    for (int y = 0; y < fine.height; ++y) {
      for (int x = 0; x < fine.width; ++x) {
        const size_t to = static_cast<size_t>(y / 2) * coarse.width + x / 2;
        const size_t from = static_cast<size_t>(y) * fine.width + x;
        coarse.max_depth[to] = std::max(coarse.max_depth[to], fine.max_depth[from]);
        if (nearest) coarse.min_depth[to] = std::min(coarse.min_depth[to], fine.min_depth[from]);
      }
    }
  }
  levels_.resize(k);
  size_t total = 0;
  for (size_t n : invalid) total += n;
  return total;
}

namespace {

// The coarsest pyramid level whose cells cover [u0, u1] x [v0, v1] with at
// most 2 x 2 of them, and those cells.
template <typename Level>
const Level& coverLevel(const std::vector<Level>& levels, int u0, int v0, int u1, int v1, Eigen::Vector4i* cells) {
  int x0 = u0 / kTile, x1 = u1 / kTile, y0 = v0 / kTile, y1 = v1 / kTile;
  size_t k = 0;
  while (k + 1 < levels.size() && (x1 - x0 > 1 || y1 - y0 > 1)) {
    x0 /= 2, x1 /= 2, y0 /= 2, y1 /= 2;
    ++k;
  }
  *cells << x0, y0, x1, y1;
  return levels[k];
}

}  // namespace

float DepthIndex::maxDepthOver(int u0, int v0, int u1, int v1) const {
  Eigen::Vector4i c;
  const Level& l = coverLevel(levels_, u0, v0, u1, v1, &c);
  float m = kNone;
  for (int y = c[1]; y <= c[3]; ++y) {
    for (int x = c[0]; x <= c[2]; ++x) m = std::max(m, l.max_depth[static_cast<size_t>(y) * l.width + x]);
  }
  return m;
}

float DepthIndex::minDepthOver(int u0, int v0, int u1, int v1) const {
  Eigen::Vector4i c;
  const Level& l = coverLevel(levels_, u0, v0, u1, v1, &c);
  if (l.min_depth.empty()) return -kInf;  // not built: no bound
  float m = kInf;
  for (int y = c[1]; y <= c[3]; ++y) {
    for (int x = c[0]; x <= c[2]; ++x) m = std::min(m, l.min_depth[static_cast<size_t>(y) * l.width + x]);
  }
  return m;
}

}  // namespace surface_nbv
