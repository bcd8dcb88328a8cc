// DepthIndex against a plain per-pixel reference: usable depths, invalid
// counts, silhouettes and the max- and min-depth bounds, on images mixing surfaces,
// depth jumps and every kind of invalid pixel.
#include "surface_nbv/map/depth_index.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace surface_nbv;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

struct Reference {
  std::vector<float> usable;
  std::vector<uint8_t> silhouette;
  size_t invalid = 0;
};

Reference reference(const DepthCamera& camera, const DepthImage& depth, float truncation, InvalidPixelPolicy policy) {
  const float lo = static_cast<float>(camera.config().min_range), hi = static_cast<float>(camera.config().max_range);
  Reference r;
  r.usable.resize(depth.data.size());
  r.silhouette.assign(depth.data.size(), 0);
  for (size_t i = 0; i < depth.data.size(); ++i) {
    const float d = depth.data[i];
    const bool ok = d >= lo && d <= hi;
    const bool clears = !ok && (policy == InvalidPixelPolicy::kClearToMaxRange ||
                                (policy == InvalidPixelPolicy::kClearInfinite && d > hi));
    r.usable[i] = ok ? d : clears ? kInf : std::nanf("");
    r.invalid += ok ? 0 : 1;
  }
  const int W = depth.width, H = depth.height;
  auto differ = [&](size_t a, size_t b) {
    const float x = r.usable[a], y = r.usable[b];
    if (std::isfinite(x) != std::isfinite(y)) return true;
    return std::isfinite(x) && std::abs(x - y) > truncation;
  };
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u) {
      const size_t i = static_cast<size_t>(v) * W + u;
      if (u + 1 < W && differ(i, i + 1)) r.silhouette[i] = r.silhouette[i + 1] = 1;
      if (v + 1 < H && differ(i, i + W)) r.silhouette[i] = r.silhouette[i + W] = 1;
    }
  return r;
}

// Planes at a few depths in blocks, a slope, and scattered invalid pixels of every kind.
DepthImage mixedImage(int width, int height, unsigned int seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  DepthImage image;
  image.resize(width, height);
  const float specials[] = {std::nanf(""), kInf, -kInf, 0.0f, 0.5f, 12.0f};
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      float d = 2.0f + 0.01f * u + ((u / 13 + v / 7) % 3) * 1.5f;
      const float p = unit(rng);
      if (p < 0.08f) d = specials[static_cast<int>(unit(rng) * 6) % 6];
      image.at(v, u) = d;
    }
  return image;
}

}  // namespace

TEST(DepthIndex, MatchesThePerPixelReference) {
  CameraConfig config;
  config.width = 203;  // not a multiple of the 8-pixel tiles
  config.height = 77;
  config.min_range = 1.0;
  config.max_range = 8.0;
  const DepthCamera camera(config);
  const DepthImage depth = mixedImage(config.width, config.height, 5);
  for (InvalidPixelPolicy policy :
       {InvalidPixelPolicy::kIgnore, InvalidPixelPolicy::kClearInfinite, InvalidPixelPolicy::kClearToMaxRange}) {
    for (int threads : {1, 2}) {
      for (float truncation : {0.3f, 1.0f}) {
        DepthIndex index;
        const size_t invalid = index.build(camera, depth, truncation, policy, threads, /*nearest=*/true);
        const Reference r = reference(camera, depth, truncation, policy);
        EXPECT_EQ(invalid, r.invalid);
        size_t usable_diff = 0, silhouette_diff = 0, silhouettes = 0;
        for (size_t i = 0; i < depth.data.size(); ++i) {
          const float a = index.usable(i), b = r.usable[i];
          usable_diff += (std::isnan(a) != std::isnan(b)) || (!std::isnan(a) && a != b);
          silhouette_diff += index.silhouette(i) != (r.silhouette[i] != 0);
          silhouettes += r.silhouette[i];
        }
        EXPECT_EQ(usable_diff, 0u) << toString(policy) << " threads " << threads;
        EXPECT_EQ(silhouette_diff, 0u) << toString(policy) << " threads " << threads << " t " << truncation;
        EXPECT_GT(silhouettes, 100u);
        EXPECT_LT(silhouettes, depth.data.size());
        // The bound over rectangles is at least every usable depth inside and
        // exactly the largest one over the whole image.
        float largest = -kInf;
        for (float x : r.usable)
          if (!std::isnan(x)) largest = std::max(largest, std::isinf(x) ? static_cast<float>(config.max_range) : x);
        EXPECT_EQ(index.maxDepthOver(0, 0, config.width - 1, config.height - 1), largest);
        // The nearest measured depth (cleared pixels do not count): at most
        // every one inside, exactly the smallest over the image.
        float nearest = kInf;
        for (float x : r.usable)
          if (std::isfinite(x)) nearest = std::min(nearest, x);
        EXPECT_EQ(index.minDepthOver(0, 0, config.width - 1, config.height - 1), nearest);
        // Without the min pyramid (the planning map's builds) there is no bound.
        DepthIndex plain;
        plain.build(camera, depth, truncation, policy, threads);
        EXPECT_EQ(plain.minDepthOver(0, 0, config.width - 1, config.height - 1), -kInf);
        EXPECT_EQ(plain.maxDepthOver(0, 0, config.width - 1, config.height - 1), largest);
        std::mt19937 rng(threads);
        for (int k = 0; k < 200; ++k) {
          int u0 = rng() % config.width, u1 = rng() % config.width, v0 = rng() % config.height,
              v1 = rng() % config.height;
          if (u0 > u1) std::swap(u0, u1);
          if (v0 > v1) std::swap(v0, v1);
          float truth = -kInf, near = kInf;
          for (int v = v0; v <= v1; ++v)
            for (int u = u0; u <= u1; ++u) {
              const float x = r.usable[static_cast<size_t>(v) * config.width + u];
              if (!std::isnan(x)) truth = std::max(truth, std::isinf(x) ? static_cast<float>(config.max_range) : x);
              if (std::isfinite(x)) near = std::min(near, x);
            }
          ASSERT_GE(index.maxDepthOver(u0, v0, u1, v1), truth) << u0 << " " << v0 << " " << u1 << " " << v1;
          ASSERT_LE(index.minDepthOver(u0, v0, u1, v1), near) << u0 << " " << v0 << " " << u1 << " " << v1;
        }
      }
    }
  }
}
