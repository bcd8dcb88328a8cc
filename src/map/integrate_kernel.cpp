#include "surface_nbv/map/integrate_kernel.h"

#include <algorithm>
#include <cmath>

#include "surface_nbv/util/simd.h"

namespace surface_nbv {
namespace {

// Centre of voxel (0, j, k) of the block, as (p0 + az k) + ay j coefficient-wise.
inline void rowStart(const BlockKernelFrame& f, const float p0[3], int j, int k, float row[3]) {
  const float kf = static_cast<float>(k), jf = static_cast<float>(j);
  for (int c = 0; c < 3; ++c) row[c] = (p0[c] + f.az[c] * kf) + f.ay[c] * jf;
}

size_t integrateBlockScalar(const BlockKernelFrame& f, const float p0[3], TsdfBlock* block) {
  const float W = static_cast<float>(f.width), H = static_cast<float>(f.height);
  const float t = f.dropoff.trunc;
  size_t n = 0;
  for (int k = 0; k < kBlockSize; ++k) {
    for (int j = 0; j < kBlockSize; ++j) {
      float row[3];
      rowStart(f, p0, j, k, row);
      TsdfVoxel* vox = &block->at(0, j, k);
      for (int i = 0; i < kBlockSize; ++i) {
        const float fi = static_cast<float>(i);
        const float x = row[0] + f.ax[0] * fi, y = row[1] + f.ax[1] * fi, z = row[2] + f.ax[2] * fi;
        if (!(z > 1e-3f) || z > f.far) continue;
        const float inv_z = 1.0f / z;
        const float uf = f.fx * x * inv_z + f.cx, vf = f.fy * y * inv_z + f.cy;
        if (!(uf >= 0.0f && uf < W && vf >= 0.0f && vf < H)) continue;
        const size_t pixel = static_cast<size_t>(vf) * f.width + static_cast<size_t>(uf);
        const float d = f.usable[pixel];
        float sdf, weight = f.frame_weight * inv_z * inv_z;
        if (std::isinf(d)) {
          if (z > f.max_range) continue;
          sdf = t;
        } else {
          sdf = d - z;  // NaN for an ignored pixel: the comparison below skips it
          if (!(sdf >= -t) || (sdf < 0.0f && f.silhouette[pixel])) continue;
          sdf = std::min(sdf, t);
          weight *= f.dropoff.share(sdf, z);
          if (!(weight > 0.0f)) continue;  // at -truncation nothing is left to add
        }
        updateVoxel(&vox[i], sdf, weight, f.max_weight);
        ++n;
      }
    }
  }
  return n;
}

#ifdef SURFACE_NBV_X86
// kBlockSize is the AVX2 vector width: one block row per vector.
static_assert(kBlockSize == 8, "the AVX2 kernel takes a block row as one vector of 8 floats");
static_assert(sizeof(TsdfVoxel) == 2 * sizeof(float), "voxels are (phi, w) pairs of floats");

__attribute__((target("avx2"))) size_t integrateBlockAvx2(const BlockKernelFrame& f, const float p0[3],
                                                          TsdfBlock* block) {
  const __m256 lane = _mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256 ax0 = _mm256_mul_ps(_mm256_set1_ps(f.ax[0]), lane);
  const __m256 ax1 = _mm256_mul_ps(_mm256_set1_ps(f.ax[1]), lane);
  const __m256 ax2 = _mm256_mul_ps(_mm256_set1_ps(f.ax[2]), lane);
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
  const __m256 near = _mm256_set1_ps(1e-3f), far = _mm256_set1_ps(f.far), max_range = _mm256_set1_ps(f.max_range);
  const __m256 W = _mm256_set1_ps(static_cast<float>(f.width)), H = _mm256_set1_ps(static_cast<float>(f.height));
  const __m256 fx = _mm256_set1_ps(f.fx), fy = _mm256_set1_ps(f.fy), cx = _mm256_set1_ps(f.cx),
               cy = _mm256_set1_ps(f.cy);
  const __m256 t = _mm256_set1_ps(f.dropoff.trunc), minus_t = _mm256_set1_ps(-f.dropoff.trunc);
  const __m256 frame_weight = _mm256_set1_ps(f.frame_weight), max_weight = _mm256_set1_ps(f.max_weight);
  // WeightDropoff::share: (trunc + sdf) scale below -start when on.
  const __m256 drop_below = _mm256_set1_ps(f.dropoff.on ? -f.dropoff.start : -INFINITY);
  const __m256 drop_scale = _mm256_set1_ps(f.dropoff.scale);
  const bool noisy = f.dropoff.on && f.dropoff.noisy;
  const __m256 drop_start = _mm256_set1_ps(f.dropoff.start), noise0 = _mm256_set1_ps(f.dropoff.noise0),
               noise1 = _mm256_set1_ps(f.dropoff.noise1), noise2 = _mm256_set1_ps(f.dropoff.noise2);
  const __m256 inf = _mm256_set1_ps(INFINITY);
  const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  const __m256i width = _mm256_set1_epi32(f.width);
  const bool cap = f.max_weight > 0.0f;
  size_t n = 0;
  for (int k = 0; k < kBlockSize; ++k) {
    for (int j = 0; j < kBlockSize; ++j) {
      float row[3];
      rowStart(f, p0, j, k, row);
      // x + ax * i with the product formed first, as in the scalar loop.
      const __m256 x = _mm256_add_ps(_mm256_set1_ps(row[0]), ax0);
      const __m256 y = _mm256_add_ps(_mm256_set1_ps(row[1]), ax1);
      const __m256 z = _mm256_add_ps(_mm256_set1_ps(row[2]), ax2);
      __m256 m = _mm256_and_ps(_mm256_cmp_ps(z, near, _CMP_GT_OQ), _mm256_cmp_ps(z, far, _CMP_LE_OQ));
      if (_mm256_movemask_ps(m) == 0) continue;
      const __m256 inv_z = _mm256_div_ps(one, z);
      const __m256 uf = _mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(fx, x), inv_z), cx);
      const __m256 vf = _mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(fy, y), inv_z), cy);
      m = _mm256_and_ps(m, _mm256_and_ps(_mm256_cmp_ps(uf, zero, _CMP_GE_OQ), _mm256_cmp_ps(uf, W, _CMP_LT_OQ)));
      m = _mm256_and_ps(m, _mm256_and_ps(_mm256_cmp_ps(vf, zero, _CMP_GE_OQ), _mm256_cmp_ps(vf, H, _CMP_LT_OQ)));
      if (_mm256_movemask_ps(m) == 0) continue;
      // Lanes outside the image are masked: their (meaningless) index is not read.
      const __m256i pixel = _mm256_add_epi32(_mm256_mullo_epi32(_mm256_cvttps_epi32(vf), width), _mm256_cvttps_epi32(uf));
      const __m256 d = _mm256_mask_i32gather_ps(zero, f.usable, pixel, m, 4);
      const __m256 weight = _mm256_mul_ps(_mm256_mul_ps(frame_weight, inv_z), inv_z);
      const __m256 is_inf = _mm256_cmp_ps(_mm256_and_ps(d, abs_mask), inf, _CMP_EQ_OQ);
      // "Free up to max range": sdf = truncation, full weight, up to max range.
      const __m256 m_inf = _mm256_and_ps(_mm256_and_ps(m, is_inf), _mm256_cmp_ps(z, max_range, _CMP_LE_OQ));
      // A measurement: within the band (NaN fails), capped, weight dropping off behind.
      const __m256 sdf_raw = _mm256_sub_ps(d, z);
      __m256 m_fin = _mm256_andnot_ps(is_inf, _mm256_and_ps(m, _mm256_cmp_ps(sdf_raw, minus_t, _CMP_GE_OQ)));
      const int behind = _mm256_movemask_ps(_mm256_and_ps(m_fin, _mm256_cmp_ps(sdf_raw, zero, _CMP_LT_OQ)));
      if (behind != 0) {  // behind a silhouette pixel a voxel is only carved, never filled
        alignas(32) int32_t pixels[8];
        alignas(32) int32_t keep[8];
        _mm256_store_si256(reinterpret_cast<__m256i*>(pixels), pixel);
        for (int i = 0; i < 8; ++i) keep[i] = (behind >> i & 1) && f.silhouette[pixels[i]] ? 0 : -1;
        m_fin = _mm256_and_ps(m_fin, _mm256_castsi256_ps(_mm256_load_si256(reinterpret_cast<const __m256i*>(keep))));
      }
      const __m256 sdf_fin = _mm256_min_ps(t, sdf_raw);
      __m256 share;
      if (!noisy) {
        share = _mm256_blendv_ps(one, _mm256_mul_ps(_mm256_add_ps(t, sdf_fin), drop_scale),
                                 _mm256_cmp_ps(sdf_fin, drop_below, _CMP_LT_OQ));
      } else {  // WeightDropoff::share with the sensor's noise, the scalar's operations in its order
        const __m256 s = _mm256_max_ps(
            drop_start, _mm256_add_ps(noise0, _mm256_mul_ps(_mm256_add_ps(noise1, _mm256_mul_ps(noise2, z)), z)));
        share = _mm256_blendv_ps(one, _mm256_div_ps(_mm256_add_ps(t, sdf_fin), _mm256_sub_ps(t, s)),
                                 _mm256_cmp_ps(sdf_fin, _mm256_sub_ps(zero, s), _CMP_LT_OQ));
      }
      const __m256 weight_fin = _mm256_mul_ps(weight, share);
      m_fin = _mm256_and_ps(m_fin, _mm256_cmp_ps(weight_fin, zero, _CMP_GT_OQ));
      const __m256 update = _mm256_or_ps(m_inf, m_fin);
      const int lanes = _mm256_movemask_ps(update);
      if (lanes == 0) continue;
      const __m256 sdf = _mm256_blendv_ps(sdf_fin, t, is_inf);
      const __m256 wn = _mm256_blendv_ps(weight_fin, weight, is_inf);
      // Voxels (phi, w) x 8 as two vectors; split into phi and w in lane order.
      float* vox = &block->at(0, j, k).phi;
      const __m256 v0 = _mm256_loadu_ps(vox), v1 = _mm256_loadu_ps(vox + 8);
      const __m256 phi = _mm256_castpd_ps(
          _mm256_permute4x64_pd(_mm256_castps_pd(_mm256_shuffle_ps(v0, v1, _MM_SHUFFLE(2, 0, 2, 0))), 0xD8));
      const __m256 w = _mm256_castpd_ps(
          _mm256_permute4x64_pd(_mm256_castps_pd(_mm256_shuffle_ps(v0, v1, _MM_SHUFFLE(3, 1, 3, 1))), 0xD8));
      const __m256 w_sum = _mm256_add_ps(w, wn);
      const __m256 phi_new = _mm256_div_ps(_mm256_add_ps(_mm256_mul_ps(phi, w), _mm256_mul_ps(sdf, wn)), w_sum);
      const __m256 w_new = cap ? _mm256_min_ps(max_weight, w_sum) : w_sum;
      // Back to (phi, w) pairs: the permutation is its own inverse, then interleave.
      const __m256d p = _mm256_permute4x64_pd(_mm256_castps_pd(_mm256_blendv_ps(phi, phi_new, update)), 0xD8);
      const __m256d q = _mm256_permute4x64_pd(_mm256_castps_pd(_mm256_blendv_ps(w, w_new, update)), 0xD8);
      _mm256_storeu_ps(vox, _mm256_unpacklo_ps(_mm256_castpd_ps(p), _mm256_castpd_ps(q)));
      _mm256_storeu_ps(vox + 8, _mm256_unpackhi_ps(_mm256_castpd_ps(p), _mm256_castpd_ps(q)));
      n += static_cast<size_t>(__builtin_popcount(static_cast<unsigned>(lanes)));
    }
  }
  return n;
}
#endif

}  // namespace

WeightDropoff::WeightDropoff(const TsdfConfig& c)
    : on(c.weight_dropoff),
      start(static_cast<float>(c.voxel_size)),
      trunc(static_cast<float>(c.truncationDistance())),
      scale(c.truncationDistance() > c.voxel_size ? static_cast<float>(1.0 / (c.truncationDistance() - c.voxel_size))
                                                  : 0.0f) {}

void WeightDropoff::setNoise(const CameraConfig& camera) {
  noise0 = static_cast<float>(2.0 * camera.sensor.noise_sigma0);
  noise1 = static_cast<float>(2.0 * camera.sensor.noise_sigma1);
  noise2 = static_cast<float>(2.0 * camera.noise_k);
  noisy = noise0 > 0.0f || noise1 > 0.0f || noise2 > 0.0f;
}

KernelIsa bestKernelIsa() {
#ifdef SURFACE_NBV_X86
  static const KernelIsa isa = [] {
    __builtin_cpu_init();  // needed when the first call comes from a static constructor
    return __builtin_cpu_supports("avx2") ? KernelIsa::kAvx2 : KernelIsa::kScalar;
  }();
  return isa;
#else
  return KernelIsa::kScalar;
#endif
}

size_t integrateBlock(const BlockKernelFrame& frame, const float p0[3], TsdfBlock* block, KernelIsa isa) {
#ifdef SURFACE_NBV_X86
  if (isa == KernelIsa::kAvx2 && bestKernelIsa() == KernelIsa::kAvx2) return integrateBlockAvx2(frame, p0, block);
#endif
  (void)isa;
  return integrateBlockScalar(frame, p0, block);
}

}  // namespace surface_nbv
