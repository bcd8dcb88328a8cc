#include "surface_nbv/map/tsdf_integrator.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <thread>
#include <unordered_map>

namespace surface_nbv {
namespace {

constexpr int kTile = 8;  // pixels per side of a depth tile

// Per-tile maximum usable depth, for culling blocks hidden behind surfaces.
// A tile with no usable pixel holds -inf (nothing can be updated through it).
struct DepthTiles {
  int tiles_x = 0, tiles_y = 0;
  std::vector<float> max_depth;

  float maxOver(int u0, int v0, int u1, int v1) const {
    float m = -std::numeric_limits<float>::infinity();
    for (int ty = v0 / kTile; ty <= v1 / kTile; ++ty) {
      const float* row = &max_depth[static_cast<size_t>(ty) * tiles_x];
      for (int tx = u0 / kTile; tx <= u1 / kTile; ++tx) m = std::max(m, row[tx]);
    }
    return m;
  }
};

void updateVoxel(TsdfVoxel* v, float sdf, float weight, float max_weight) {
  const float w = v->w + weight;
  v->phi = (v->phi * v->w + sdf * weight) / w;
  v->w = max_weight > 0.0f ? std::min(w, max_weight) : w;
}

template <typename Fn>
void parallelFor(size_t n, int threads, Fn&& fn) {
  if (threads <= 1 || n < 2) {
    for (size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::atomic<size_t> next{0};
  auto worker = [&]() {
    for (size_t i = next.fetch_add(1); i < n; i = next.fetch_add(1)) fn(i);
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

}  // namespace

TsdfIntegrator::TsdfIntegrator(TsdfMap* map) : map_(map) {}

Status TsdfIntegrator::integrateDepth(const DepthCamera& camera, const DepthImage& depth, const Transform& T_W_C,
                                      IntegrationStats* stats_out) {
  IntegrationStats stats;
  const TsdfConfig& cfg = map_->config();
  const int W = camera.width(), H = camera.height();
  if (depth.width != W || depth.height != H || depth.data.size() != static_cast<size_t>(W) * H) {
    return Status::Error("depth image is " + std::to_string(depth.width) + "x" + std::to_string(depth.height) +
                         ", camera expects " + std::to_string(W) + "x" + std::to_string(H));
  }
  if (!T_W_C.matrix().allFinite()) return Status::Error("camera pose is not finite");
  if (!cfg.bounds.contains(T_W_C.translation())) return Status::Error("camera pose is outside the map bounds");

  const float trunc = static_cast<float>(cfg.truncationDistance());
  const float min_range = static_cast<float>(camera.config().min_range);
  const float max_range = static_cast<float>(camera.config().max_range);
  const bool clear = cfg.invalid_pixels == InvalidPixelPolicy::kClearToMaxRange;

  // Usable depth per pixel: a measurement, +inf for "free up to max range", NaN for nothing.
  std::vector<float> usable(depth.data.size());
  DepthTiles tiles;
  tiles.tiles_x = (W + kTile - 1) / kTile;
  tiles.tiles_y = (H + kTile - 1) / kTile;
  tiles.max_depth.assign(static_cast<size_t>(tiles.tiles_x) * tiles.tiles_y, -std::numeric_limits<float>::infinity());
  for (int v = 0; v < H; ++v) {
    for (int u = 0; u < W; ++u) {
      const size_t i = static_cast<size_t>(v) * W + u;
      const float d = depth.data[i];
      float use;
      float reach;
      if (std::isfinite(d) && d >= min_range && d <= max_range) {
        use = d;
        reach = d;
      } else {
        ++stats.invalid_pixels;
        use = clear ? std::numeric_limits<float>::infinity() : std::numeric_limits<float>::quiet_NaN();
        reach = clear ? max_range : -std::numeric_limits<float>::infinity();
      }
      usable[i] = use;
      float& m = tiles.max_depth[static_cast<size_t>(v / kTile) * tiles.tiles_x + u / kTile];
      m = std::max(m, reach);
    }
  }

  // Silhouette pixels: next to a pixel with no usable depth or with a depth
  // more than the truncation away. A voxel behind a silhouette cannot be told
  // from one inside the object, so such pixels only carve free space.
  std::vector<uint8_t> silhouette(usable.size(), 0);
  auto jump = [&](size_t a, size_t b) {
    const float da = usable[a], db = usable[b];
    const bool va = std::isfinite(da), vb = std::isfinite(db);
    if (va != vb || (va && std::abs(da - db) > trunc)) silhouette[a] = silhouette[b] = 1;
  };
  for (int v = 0; v < H; ++v) {
    for (int u = 0; u < W; ++u) {
      const size_t i = static_cast<size_t>(v) * W + u;
      if (u + 1 < W) jump(i, i + 1);
      if (v + 1 < H) jump(i, i + W);
    }
  }

  // Candidate blocks: the frustum's bounding box, culled block by block.
  const Transform T_C_W = T_W_C.inverse();
  const double far = max_range + trunc;
  AlignedBox frustum;
  frustum.extend(T_W_C.translation());
  for (double c : {-0.5, W - 0.5}) {
    for (double r : {-0.5, H - 0.5}) frustum.extend(T_W_C * (camera.pixelRay(c, r) * far));
  }
  const double block_len = cfg.voxel_size * kBlockSize;
  const Eigen::Vector3i lo =
      ((frustum.min - cfg.bounds.min) / block_len).array().floor().cast<int>().max(0).matrix();
  const Eigen::Vector3i hi = ((frustum.max - cfg.bounds.min) / block_len)
                                 .array()
                                 .floor()
                                 .cast<int>()
                                 .min(map_->gridBlocks().array() - 1)
                                 .matrix();
  std::vector<TsdfBlock*> work;
  for (int z = lo.z(); z <= hi.z(); ++z) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int x = lo.x(); x <= hi.x(); ++x) {
        ++stats.blocks_considered;
        const Eigen::Vector3d origin = cfg.bounds.min + Eigen::Vector3d(x, y, z) * block_len;
        double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
        double umin = zmin, umax = -zmin, vmin = zmin, vmax = -zmin;
        bool behind = false;
        for (int c = 0; c < 8; ++c) {
          const Eigen::Vector3d corner = origin + block_len * Eigen::Vector3d(c & 1, (c >> 1) & 1, (c >> 2) & 1);
          const Eigen::Vector3d p = T_C_W * corner;
          zmin = std::min(zmin, p.z());
          zmax = std::max(zmax, p.z());
          if (p.z() <= 1e-6) {
            behind = true;
            continue;
          }
          const double u = camera.fx() * p.x() / p.z() + camera.cx(), v = camera.fy() * p.y() / p.z() + camera.cy();
          umin = std::min(umin, u), umax = std::max(umax, u), vmin = std::min(vmin, v), vmax = std::max(vmax, v);
        }
        if (zmax <= 0.0 || zmin > far) continue;
        if (behind) umin = vmin = -0.5, umax = W - 0.5, vmax = H - 0.5;  // straddles the image plane
        if (umax < -0.5 || umin > W - 0.5 || vmax < -0.5 || vmin > H - 0.5) continue;
        const int u0 = std::max(0, static_cast<int>(std::floor(umin + 0.5)));
        const int u1 = std::min(W - 1, static_cast<int>(std::floor(umax + 0.5)));
        const int v0 = std::max(0, static_cast<int>(std::floor(vmin + 0.5)));
        const int v1 = std::min(H - 1, static_cast<int>(std::floor(vmax + 0.5)));
        if (zmin > tiles.maxOver(u0, v0, u1, v1) + trunc) continue;  // hidden behind every surface
        TsdfBlock* b = map_->allocateBlock(Eigen::Vector3i(x, y, z));
        if (b == nullptr) {
          ++stats.blocks_refused;
          continue;
        }
        work.push_back(b);
      }
    }
  }

  // Projective update of every voxel of the candidate blocks.
  const uint64_t stamp = map_->beginChange();
  const Eigen::Matrix3f R = T_C_W.linear().cast<float>();
  const float vs = static_cast<float>(cfg.voxel_size);
  const Eigen::Vector3f ax = R.col(0) * vs, ay = R.col(1) * vs, az = R.col(2) * vs;
  const float fx = static_cast<float>(camera.fx()), fy = static_cast<float>(camera.fy());
  const float cx = static_cast<float>(camera.cx()) + 0.5f, cy = static_cast<float>(camera.cy()) + 0.5f;
  const float max_weight = cfg.max_weight;
  std::vector<size_t> updated(work.size(), 0);
  parallelFor(work.size(), cfg.threads, [&](size_t bi) {
    TsdfBlock* b = work[bi];
    const Eigen::Vector3d c0 = cfg.bounds.min + (b->index.cast<double>() * kBlockSize).cast<double>() * cfg.voxel_size +
                               Eigen::Vector3d::Constant(0.5 * cfg.voxel_size);
    const Eigen::Vector3f p0 = (T_C_W * c0).cast<float>();
    size_t n = 0;
    for (int k = 0; k < kBlockSize; ++k) {
      for (int j = 0; j < kBlockSize; ++j) {
        const Eigen::Vector3f row = p0 + az * static_cast<float>(k) + ay * static_cast<float>(j);
        TsdfVoxel* vox = &b->at(0, j, k);
        for (int i = 0; i < kBlockSize; ++i) {
          const Eigen::Vector3f p = row + ax * static_cast<float>(i);
          const float z = p.z();
          if (!(z > 1e-3f) || z > far) continue;
          const float inv_z = 1.0f / z;
          const float uf = fx * p.x() * inv_z + cx, vf = fy * p.y() * inv_z + cy;
          if (!(uf >= 0.0f && uf < W && vf >= 0.0f && vf < H)) continue;
          const size_t pixel = static_cast<size_t>(vf) * W + static_cast<size_t>(uf);
          const float d = usable[pixel];
          float sdf;
          if (std::isinf(d)) {
            if (z > max_range) continue;
            sdf = trunc;
          } else {
            sdf = d - z;  // NaN for an ignored pixel: the comparison below skips it
            if (!(sdf >= -trunc) || (sdf < 0.0f && silhouette[pixel])) continue;
            sdf = std::min(sdf, trunc);
          }
          updateVoxel(&vox[i], sdf, inv_z * inv_z, max_weight);
          ++n;
        }
      }
    }
    if (n > 0) b->change_stamp = stamp;
    updated[bi] = n;
  });
  for (size_t n : updated) {
    stats.voxels_updated += n;
    stats.blocks_updated += n > 0 ? 1 : 0;
  }
  if (stats_out != nullptr) *stats_out = stats;
  return Status::Ok();
}

Status TsdfIntegrator::integratePoints(const std::vector<Eigen::Vector3f>& points_S, const Transform& T_W_S,
                                       double max_range, IntegrationStats* stats_out) {
  IntegrationStats stats;
  const TsdfConfig& cfg = map_->config();
  if (!T_W_S.matrix().allFinite()) return Status::Error("sensor pose is not finite");
  if (!cfg.bounds.contains(T_W_S.translation())) return Status::Error("sensor pose is outside the map bounds");
  if (!std::isfinite(max_range) || max_range <= 0.0) return Status::Error("max_range expected > 0");
  const bool clear = cfg.invalid_pixels == InvalidPixelPolicy::kClearToMaxRange;
  const double trunc = cfg.truncationDistance();
  const Eigen::Vector3d o = T_W_S.translation();

  // One update per voxel per cloud: the mean sdf of the rays through it.
  struct Accum {
    double sdf_sum = 0.0;
    int count = 0;
    double dist = 0.0;
  };
  std::unordered_map<int64_t, Accum> touched;
  const Eigen::Vector3i grid = map_->gridVoxels();
  auto key = [&](const Eigen::Vector3i& v) {
    return static_cast<int64_t>(v.x()) + static_cast<int64_t>(grid.x()) * (v.y() + static_cast<int64_t>(grid.y()) * v.z());
  };
  const double step = 0.5 * cfg.voxel_size;
  for (const Eigen::Vector3f& q : points_S) {
    const Eigen::Vector3d p_S = q.cast<double>();
    const double range = p_S.norm();
    bool valid = p_S.allFinite() && range > 1e-6 && range <= max_range;
    if (!valid) {
      ++stats.invalid_pixels;
      if (!clear || !p_S.allFinite() || range <= 1e-6) continue;
    }
    const Eigen::Vector3d dir = T_W_S.linear() * (p_S / range);
    const double end = valid ? range + trunc : max_range;
    Eigen::Vector3i last(-1, -1, -1);
    for (double t = step; t <= end; t += step) {
      Eigen::Vector3i v;
      if (!map_->voxelIndex(o + t * dir, &v)) break;
      if (v == last) continue;  // half-voxel steps visit most voxels twice
      last = v;
      const double along = (map_->voxelCenter(v) - o).dot(dir);
      const double sdf = valid ? std::min(range - along, trunc) : trunc;
      if (sdf < -trunc) break;
      Accum& a = touched[key(v)];
      a.sdf_sum += sdf;
      a.dist = along;
      ++a.count;
    }
  }
  const uint64_t stamp = map_->beginChange();
  for (const auto& kv : touched) {
    const int64_t k = kv.first;
    const Eigen::Vector3i v(static_cast<int>(k % grid.x()), static_cast<int>((k / grid.x()) % grid.y()),
                            static_cast<int>(k / (static_cast<int64_t>(grid.x()) * grid.y())));
    TsdfBlock* b = map_->allocateBlock(TsdfMap::blockOfVoxel(v));
    if (b == nullptr) {
      ++stats.blocks_refused;
      continue;
    }
    const Eigen::Vector3i l = TsdfMap::localOfVoxel(v);
    const double dist = std::max(kv.second.dist, 1e-3);
    updateVoxel(&b->at(l.x(), l.y(), l.z()), static_cast<float>(kv.second.sdf_sum / kv.second.count),
                static_cast<float>(1.0 / (dist * dist)), cfg.max_weight);
    b->change_stamp = stamp;
    ++stats.voxels_updated;
  }
  stats.blocks_updated = map_->blocksChangedSince(stamp - 1).size();
  if (stats_out != nullptr) *stats_out = stats;
  return Status::Ok();
}

}  // namespace surface_nbv
