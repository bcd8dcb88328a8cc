#include "surface_nbv/map/tsdf_integrator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "surface_nbv/map/integrate_kernel.h"
#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {
namespace {

// A side plane of the frustum through the camera centre: inside where
// (n . p) >= 0, with n normalised.
struct SidePlane {
  Eigen::Vector3d n;
  double distance(const Eigen::Vector3d& p_C) const { return n.dot(p_C); }
};

}  // namespace

TsdfIntegrator::TsdfIntegrator(TsdfMap* map) : map_(map) {}

std::vector<TsdfBlock*> TsdfIntegrator::candidateBlocks(const DepthCamera& camera, const Transform& T_W_C,
                                                        IntegrationStats* stats) {
  const TsdfConfig& cfg = map_->config();
  const int W = camera.width(), H = camera.height();
  const double trunc = cfg.truncationDistance();
  const double far = camera.config().max_range + trunc;
  const Transform T_C_W = T_W_C.inverse();
  AlignedBox frustum;
  frustum.extend(T_W_C.translation());
  for (double c : {-0.5, W - 0.5}) {
    for (double r : {-0.5, H - 0.5}) frustum.extend(T_W_C * (camera.pixelRay(c, r) * far));
  }
  const double block_len = cfg.voxel_size * kBlockSize;
  const double radius = 0.5 * std::sqrt(3.0) * block_len;
  const Eigen::Vector3i lo = ((frustum.min - cfg.bounds.min) / block_len).array().floor().cast<int>().max(0).matrix();
  const Eigen::Vector3i hi = ((frustum.max - cfg.bounds.min) / block_len)
                                 .array()
                                 .floor()
                                 .cast<int>()
                                 .min(map_->gridBlocks().array() - 1)
                                 .matrix();
  const double left = (-0.5 - camera.cx()) / camera.fx(), right = (W - 0.5 - camera.cx()) / camera.fx();
  const double top = (-0.5 - camera.cy()) / camera.fy(), bottom = (H - 0.5 - camera.cy()) / camera.fy();
  const SidePlane planes[4] = {{Eigen::Vector3d(1, 0, -left).normalized()},
                               {Eigen::Vector3d(-1, 0, right).normalized()},
                               {Eigen::Vector3d(0, 1, -top).normalized()},
                               {Eigen::Vector3d(0, -1, bottom).normalized()}};
  const float t = static_cast<float>(trunc);

  // Cull in parallel by z slices of the block grid, allocate serially.
  const int slices = std::max(0, hi.z() - lo.z() + 1);
  std::vector<std::vector<Eigen::Vector3i>> kept(static_cast<size_t>(slices));
  std::vector<size_t> considered(static_cast<size_t>(slices), 0);
  parallelFor(static_cast<size_t>(slices), threads(), [&](size_t slice) {
    const int z = lo.z() + static_cast<int>(slice);
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int x = lo.x(); x <= hi.x(); ++x) {
        ++considered[slice];
        const Eigen::Vector3d origin = cfg.bounds.min + Eigen::Vector3d(x, y, z) * block_len;
        const Eigen::Vector3d centre_C = T_C_W * (origin + Eigen::Vector3d::Constant(0.5 * block_len));
        if (centre_C.z() < -radius || centre_C.z() > far + radius) continue;
        bool outside = false;
        for (const SidePlane& p : planes) outside = outside || p.distance(centre_C) < -radius;
        if (outside) continue;
        double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
        double umin = zmin, umax = -zmin, vmin = zmin, vmax = -zmin;
        bool behind = false;
        for (int c = 0; c < 8; ++c) {
          const Eigen::Vector3d p = T_C_W * (origin + block_len * Eigen::Vector3d(c & 1, (c >> 1) & 1, (c >> 2) & 1));
          zmin = std::min(zmin, p.z());
          zmax = std::max(zmax, p.z());
          if (p.z() <= 1e-6) {
            behind = true;
            continue;
          }
          const double u = camera.fx() * p.x() / p.z() + camera.cx(), v = camera.fy() * p.y() / p.z() + camera.cy();
          umin = std::min(umin, u), umax = std::max(umax, u), vmin = std::min(vmin, v), vmax = std::max(vmax, v);
        }
        if (behind) umin = vmin = -0.5, umax = W - 0.5, vmax = H - 0.5;  // straddles the image plane
        if (umax < -0.5 || umin > W - 0.5 || vmax < -0.5 || vmin > H - 0.5) continue;
        const int u0 = std::max(0, static_cast<int>(std::floor(umin + 0.5)));
        const int u1 = std::min(W - 1, static_cast<int>(std::floor(umax + 0.5)));
        const int v0 = std::max(0, static_cast<int>(std::floor(vmin + 0.5)));
        const int v1 = std::min(H - 1, static_cast<int>(std::floor(vmax + 0.5)));
        if (zmin > index_.maxDepthOver(u0, v0, u1, v1) + t) continue;  // hidden behind every surface
        // band_allocation: a new block wholly in front of every surface by more than t.
        if (cfg.band_allocation && zmax < index_.minDepthOver(u0, v0, u1, v1) - t &&
            map_->block(Eigen::Vector3i(x, y, z)) == nullptr) {
          continue;
        }
        kept[slice].emplace_back(x, y, z);
      }
    }
  });
  std::vector<TsdfBlock*> work;
  for (size_t slice = 0; slice < kept.size(); ++slice) {
    stats->blocks_considered += considered[slice];
    for (const Eigen::Vector3i& index : kept[slice]) {
      TsdfBlock* b = map_->allocateBlock(index);
      if (b == nullptr) {
        ++stats->blocks_refused;
        continue;
      }
      work.push_back(b);
    }
  }
  return work;
}

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
  const float max_range = static_cast<float>(camera.config().max_range);
  const float far = max_range + trunc;
  stats.invalid_pixels = index_.build(camera, depth, trunc, cfg.invalid_pixels, threads(), cfg.band_allocation);
  const std::vector<TsdfBlock*> work = candidateBlocks(camera, T_W_C, &stats);

  // Projective update of every voxel of the candidate blocks (integrate_kernel.h).
  const uint64_t stamp = map_->beginChange();
  const Transform T_C_W = T_W_C.inverse();
  const Eigen::Matrix3f R = T_C_W.linear().cast<float>();
  const float vs = static_cast<float>(cfg.voxel_size);
  BlockKernelFrame frame;
  for (int c = 0; c < 3; ++c) {
    frame.ax[c] = R(c, 0) * vs;
    frame.ay[c] = R(c, 1) * vs;
    frame.az[c] = R(c, 2) * vs;
  }
  frame.fx = static_cast<float>(camera.fx());
  frame.fy = static_cast<float>(camera.fy());
  frame.cx = static_cast<float>(camera.cx()) + 0.5f;
  frame.cy = static_cast<float>(camera.cy()) + 0.5f;
  frame.width = W;
  frame.height = H;
  frame.far = far;
  frame.max_range = max_range;
  frame.frame_weight = weight_scale_;
  frame.max_weight = cfg.max_weight;
  frame.dropoff = WeightDropoff(cfg);
  frame.dropoff.setNoise(camera.config());
  frame.usable = index_.usableData();
  frame.silhouette = index_.silhouetteData();
  const KernelIsa isa = kernel_isa_;
  std::vector<size_t> updated(work.size(), 0);
  parallelFor(work.size(), threads(), [&](size_t bi) {
    TsdfBlock* b = work[bi];
    const Eigen::Vector3d c0 = cfg.bounds.min + (b->index.cast<double>() * kBlockSize) * cfg.voxel_size +
                               Eigen::Vector3d::Constant(0.5 * cfg.voxel_size);
    const Eigen::Vector3f p0 = (T_C_W * c0).cast<float>();
    const size_t n = integrateBlock(frame, p0.data(), b, isa);
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
  const bool clear_all = cfg.invalid_pixels == InvalidPixelPolicy::kClearToMaxRange;
  const bool clear_inf = cfg.invalid_pixels == InvalidPixelPolicy::kClearInfinite;
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
      // A point cloud has no direction for a point at infinity, so with
      // clear_inf only finite points beyond max_range clear free space.
      const bool finite = p_S.allFinite() && range > 1e-6;
      const bool clears = finite && (clear_all || (clear_inf && range > max_range));
      if (!clears) continue;
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
  const WeightDropoff dropoff(cfg);
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
    const float sdf = static_cast<float>(kv.second.sdf_sum / kv.second.count);
    const float weight = static_cast<float>(weight_scale_ / (dist * dist)) * dropoff.share(sdf, static_cast<float>(dist));
    if (!(weight > 0.0f)) continue;
    updateVoxel(&b->at(l.x(), l.y(), l.z()), sdf, weight, cfg.max_weight);
    b->change_stamp = stamp;
    ++stats.voxels_updated;
  }
  stats.blocks_updated = map_->blocksChangedSince(stamp - 1).size();
  if (stats_out != nullptr) *stats_out = stats;
  return Status::Ok();
}

Status TsdfIntegrator::markFree(const Eigen::Vector3d& center, double radius, size_t* changed) {
  if (!center.allFinite() || !std::isfinite(radius) || radius <= 0.0 || radius > 50.0) {
    return Status::Error("markFree expects a finite centre and a radius in (0, 50] m");
  }
  const TsdfConfig& cfg = map_->config();
  const float trunc = static_cast<float>(cfg.truncationDistance());
  const uint64_t stamp = map_->beginChange();
  const double h = map_->voxelSize();
  const int r = static_cast<int>(std::ceil(radius / h)) + 1;
  Eigen::Vector3i c;
  size_t n = 0;
  if (!map_->voxelIndex(center, &c)) {
    if (changed) *changed = 0;
    return Status::Error("markFree centre is outside the map bounds");
  }
  for (int dz = -r; dz <= r; ++dz) {
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        const Eigen::Vector3i v = c + Eigen::Vector3i(dx, dy, dz);
        if (!map_->voxelInBounds(v) || (map_->voxelCenter(v) - center).norm() > radius) continue;
        TsdfVoxel* voxel = map_->allocateVoxel(v);
        if (voxel == nullptr || voxel->w >= cfg.w_th) continue;
        voxel->phi = trunc;
        voxel->w = cfg.w_th;
        map_->mutableBlock(TsdfMap::blockOfVoxel(v))->change_stamp = stamp;
        ++n;
      }
    }
  }
  if (changed) *changed = n;
  return Status::Ok();
}

}  // namespace surface_nbv
