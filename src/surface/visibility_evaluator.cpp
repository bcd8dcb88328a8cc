#include "surface_nbv/surface/visibility_evaluator.h"

#include <algorithm>
#include <cmath>

#include "surface_nbv/surface/chunked_for.h"

namespace surface_nbv {
namespace {

// Camera axes of a camera with yaw on a level UAV, its mount pitched down by
// `pitch` [rad]: forward, right, down (world frame).
struct CameraAxes {
  Eigen::Vector3d forward, right, down;
  CameraAxes(double yaw, double pitch)
      : forward(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), -std::sin(pitch)),
        right(std::sin(yaw), -std::cos(yaw), 0.0),
        down(-std::sin(pitch) * std::cos(yaw), -std::sin(pitch) * std::sin(yaw), -std::cos(pitch)) {}
};

}  // namespace

VisibilityEvaluator::VisibilityEvaluator(const SurfaceConfig& config) : config_(config) {
  const double h = 0.5 * config_.camera.hfov_deg * M_PI / 180.0, v = 0.5 * config_.camera.vfov_deg * M_PI / 180.0;
  tan_half_h_ = std::tan(h);
  tan_half_v_ = std::tan(v);
  sin_half_h_ = std::sin(h);
  cos_half_h_ = std::cos(h);
  sin_half_v_ = std::sin(v);
  cos_half_v_ = std::cos(v);
  pitch_ = config_.camera.pitch_deg * M_PI / 180.0;
}

bool VisibilityEvaluator::inFrustum(const Viewpoint& viewpoint, const Eigen::Vector3d& p_W) const {
  const CameraAxes axes(viewpoint.yaw, pitch_);
  const Eigen::Vector3d d = p_W - viewpoint.position;
  const double z = d.dot(axes.forward);
  if (z < config_.camera.min_range || z > config_.camera.max_range) return false;
  return std::abs(d.dot(axes.right)) <= z * tan_half_h_ && std::abs(d.dot(axes.down)) <= z * tan_half_v_;
}

VisibilityEvaluator::BlockIndex VisibilityEvaluator::index(const VoxelStateGrid& grid,
                                                           const std::vector<Ise>& ises) const {
  BlockIndex out;
  out.begin.assign(grid.numBlockSlots() + 1, 0);
  std::vector<uint32_t> slot(ises.size());
  for (size_t i = 0; i < ises.size(); ++i) {
    slot[i] = static_cast<uint32_t>(grid.blockSlot(TsdfMap::blockOfVoxel(ises[i].voxel)));
    ++out.begin[slot[i] + 1];
  }
  for (size_t s = 1; s < out.begin.size(); ++s) out.begin[s] += out.begin[s - 1];
  std::vector<uint32_t> next(out.begin.begin(), out.begin.end() - 1);
  out.order.resize(ises.size());
  for (size_t i = 0; i < ises.size(); ++i) out.order[next[slot[i]]++] = static_cast<uint32_t>(i);
  return out;
}

void VisibilityEvaluator::visibleFrom(const VoxelRayCaster& rays, const BlockIndex& index,
                                      const std::vector<Ise>& ises, const Viewpoint& viewpoint,
                                      std::vector<uint32_t>* visible, uint64_t* steps) const {
  const VoxelStateGrid& grid = rays.grid();
  const CameraAxes axes(viewpoint.yaw, pitch_);
  const Eigen::Vector3d& p = viewpoint.position;
  const VoxelRayCaster::Origin from = rays.origin(p);
  const double far = config_.camera.max_range, near = config_.camera.min_range;
  // Bounding box of the frustum: the apex and the four far corners.
  Eigen::Vector3d lo = p, hi = p;
  for (int sx = -1; sx <= 1; sx += 2) {
    for (int sy = -1; sy <= 1; sy += 2) {
      const Eigen::Vector3d c =
          p + far * (axes.forward + sx * tan_half_h_ * axes.right + sy * tan_half_v_ * axes.down);
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
  }
  const double block_size = grid.voxelSize() * kBlockSize;
  const Eigen::Vector3i& g = grid.gridBlocks();
  const Eigen::Vector3i b_lo = ((lo - grid.origin()) / block_size).array().floor().cast<int>().max(0);
  const Eigen::Vector3i b_hi =
      ((hi - grid.origin()) / block_size).array().floor().cast<int>().min((g.array() - 1));
  const double radius = 0.5 * std::sqrt(3.0) * block_size;
  visible->clear();
  for (int bz = b_lo.z(); bz <= b_hi.z(); ++bz) {
    for (int by = b_lo.y(); by <= b_hi.y(); ++by) {
      for (int bx = b_lo.x(); bx <= b_hi.x(); ++bx) {
        const size_t slot = grid.blockSlot(Eigen::Vector3i(bx, by, bz));
        const uint32_t first = index.begin[slot], last = index.begin[slot + 1];
        if (first == last) continue;
        // Sphere around the block against the frustum's six planes.
        const Eigen::Vector3d c =
            grid.origin() + (Eigen::Vector3d(bx, by, bz).array() + 0.5).matrix() * block_size - p;
        const double z = c.dot(axes.forward), x = c.dot(axes.right), y = c.dot(axes.down);
        if (z < near - radius || z > far + radius) continue;
        if (std::abs(x) * cos_half_h_ - z * sin_half_h_ > radius) continue;
        if (std::abs(y) * cos_half_v_ - z * sin_half_v_ > radius) continue;
        for (uint32_t k = first; k < last; ++k) {
          const uint32_t i = index.order[k];
          const Eigen::Vector3d d = ises[i].position - p;
          const double dz = d.dot(axes.forward);
          if (dz < near || dz > far) continue;
          if (std::abs(d.dot(axes.right)) > dz * tan_half_h_ || std::abs(d.dot(axes.down)) > dz * tan_half_v_) {
            continue;
          }
          if (rays.clear(from, ises[i].voxel, steps)) visible->push_back(i);
        }
      }
    }
  }
  std::sort(visible->begin(), visible->end());
}

uint64_t VisibilityEvaluator::evaluate(const VoxelRayCaster& rays, const std::vector<Ise>& ises,
                                       std::vector<Viewpoint>* viewpoints, const std::vector<uint8_t>* todo,
                                       std::vector<uint64_t>* steps_out) const {
  const BlockIndex block_index = index(rays.grid(), ises);
  std::vector<uint64_t> steps(viewpoints->size(), 0);
  parallelForChunked(viewpoints->size(), config_.threads, 8, [&](size_t i) {
    if (todo != nullptr && !(*todo)[i]) return;
    visibleFrom(rays, block_index, ises, (*viewpoints)[i], &(*viewpoints)[i].visible, &steps[i]);
  });
  uint64_t total = 0;
  for (uint64_t s : steps) total += s;
  if (steps_out != nullptr) *steps_out = std::move(steps);
  return total;
}

}  // namespace surface_nbv
