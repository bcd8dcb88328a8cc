#include "surface_nbv/map/depth_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {
namespace {

constexpr int kTile = 8;
constexpr float kNone = -std::numeric_limits<float>::infinity();

}  // namespace

size_t DepthIndex::build(const DepthCamera& camera, const DepthImage& depth, float truncation,
                         InvalidPixelPolicy policy, int threads) {
  const int W = depth.width, H = depth.height;
  const float min_range = static_cast<float>(camera.config().min_range);
  const float max_range = static_cast<float>(camera.config().max_range);
  const bool clear_all = policy == InvalidPixelPolicy::kClearToMaxRange;
  const bool clear_inf = policy == InvalidPixelPolicy::kClearInfinite;
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  usable_.resize(depth.data.size());
  silhouette_.assign(depth.data.size(), 0);
  if (levels_.empty()) levels_.resize(1);
  Level& base = levels_[0];
  base.width = (W + kTile - 1) / kTile;
  base.height = (H + kTile - 1) / kTile;
  base.max_depth.assign(static_cast<size_t>(base.width) * base.height, kNone);

  // Pass 1, by bands of tile rows: usable depth, tile maxima, invalid count.
  std::vector<size_t> invalid(static_cast<size_t>(base.height), 0);
  parallelFor(static_cast<size_t>(base.height), threads, [&](size_t ty) {
    const int v_end = std::min(H, static_cast<int>(ty + 1) * kTile);
    float* tile_max = &base.max_depth[ty * base.width];
    for (int v = static_cast<int>(ty) * kTile; v < v_end; ++v) {
      const float* in = &depth.data[static_cast<size_t>(v) * W];
      float* out = &usable_[static_cast<size_t>(v) * W];
      for (int u = 0; u < W; ++u) {
        const float d = in[u];
        const bool ok = d >= min_range && d <= max_range;  // false for NaN
        const bool clears = !ok && (clear_all || (clear_inf && d > max_range));
        out[u] = ok ? d : clears ? inf : nan;
        invalid[ty] += ok ? 0 : 1;
        float& m = tile_max[u / kTile];
        m = std::max(m, ok ? d : clears ? max_range : kNone);
      }
    }
  });
  // Pass 2: silhouettes, comparing each pixel with its right and lower neighbours.
  parallelFor(static_cast<size_t>(H), threads, [&](size_t row) {
    const int v = static_cast<int>(row);
    const float* a = &usable_[static_cast<size_t>(v) * W];
    const float* below = v + 1 < H ? a + W : nullptr;
    uint8_t* s = &silhouette_[static_cast<size_t>(v) * W];
    for (int u = 0; u < W; ++u) {
      const bool va = std::isfinite(a[u]);
      if (u + 1 < W) {
        const bool vb = std::isfinite(a[u + 1]);
        if (va != vb || (va && std::abs(a[u] - a[u + 1]) > truncation)) s[u] = s[u + 1] = 1;
      }
      if (below != nullptr) {
        const bool vb = std::isfinite(below[u]);
        if (va != vb || (va && std::abs(a[u] - below[u]) > truncation)) s[u] = s[u + W] = 1;
      }
    }
  });
  // Pyramid: each level halves the previous one with max.
  size_t k = 1;
  for (; levels_[k - 1].width > 1 || levels_[k - 1].height > 1; ++k) {
    if (levels_.size() <= k) levels_.emplace_back();
    const Level& fine = levels_[k - 1];
    Level& coarse = levels_[k];
    coarse.width = (fine.width + 1) / 2;
    coarse.height = (fine.height + 1) / 2;
    coarse.max_depth.assign(static_cast<size_t>(coarse.width) * coarse.height, kNone);
    for (int y = 0; y < fine.height; ++y) {
      for (int x = 0; x < fine.width; ++x) {
        float& m = coarse.max_depth[static_cast<size_t>(y / 2) * coarse.width + x / 2];
        m = std::max(m, fine.max_depth[static_cast<size_t>(y) * fine.width + x]);
      }
    }
  }
  levels_.resize(k);
  size_t total = 0;
  for (size_t n : invalid) total += n;
  return total;
}

float DepthIndex::maxDepthOver(int u0, int v0, int u1, int v1) const {
  int x0 = u0 / kTile, x1 = u1 / kTile, y0 = v0 / kTile, y1 = v1 / kTile;
  size_t k = 0;
  while (k + 1 < levels_.size() && (x1 - x0 > 1 || y1 - y0 > 1)) {
    x0 /= 2, x1 /= 2, y0 /= 2, y1 /= 2;
    ++k;
  }
  const Level& l = levels_[k];
  float m = kNone;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) m = std::max(m, l.max_depth[static_cast<size_t>(y) * l.width + x]);
  }
  return m;
}

}  // namespace surface_nbv
