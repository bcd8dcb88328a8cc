#include "surface_nbv/map/collision_map.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <dynamicEDT3D/dynamicEDT3D.h>

namespace surface_nbv {

// DynamicEDT3D keeps its cells protected; this reads them without the
// library's out-of-line, bounds-checked accessors (the caller checks).
class CollisionMap::Edt : public DynamicEDT3D {
 public:
  explicit Edt(int cap_cells) : DynamicEDT3D(cap_cells * cap_cells) {}

  int sqCells(const Eigen::Vector3i& c) const { return data[c.x()][c.y()][c.z()].sqdist; }
  // The cells (x, y, 0 .. z-1), contiguous.
  const dataCell* row(int x, int y) const { return data[x][y]; }
  // The nearest obstacle cell, false when none is within the cap.
  bool nearest(int x, int y, int z, Eigen::Vector3i* obstacle) const {
    const dataCell& d = data[x][y][z];
    if (d.sqdist >= maxDist_squared || d.obstX == invalidObstData) return false;
    *obstacle = Eigen::Vector3i(d.obstX, d.obstY, d.obstZ);
    return true;
  }
  static constexpr size_t kCellBytes = sizeof(dataCell) + sizeof(bool);
};

Status CollisionConfig::validate() const {
  if (!std::isfinite(max_distance) || max_distance < 2.0) {
    return Status::Error("max_distance expected >= 2.0 (twice the 1 m collision radius)");
  }
  if (!std::isfinite(min_cell_size) || min_cell_size < 0.0) return Status::Error("min_cell_size expected >= 0");
  return Status::Ok();
}

int CollisionMap::voxelsPerCellFor(double voxel_size, const CollisionConfig& config) {
  int factor = std::max(1, static_cast<int>(std::ceil(config.min_cell_size / voxel_size - 1e-9)));
  while (std::ceil(config.max_distance / (factor * voxel_size)) + 2 > kMaxCapCells) ++factor;
  return factor;
}

CollisionMap::CollisionMap(const TsdfMap& map, const CollisionConfig& config) : config_(config) { rebuild(map); }

CollisionMap::~CollisionMap() = default;

void CollisionMap::rebuild(const TsdfMap& map) {
  static std::atomic<uint64_t> builds{0};
  build_id_ = ++builds;
  origin_ = map.config().bounds.min;
  bounds_max_ = map.config().bounds.max;
  grid_voxels_ = map.gridVoxels();
  factor_ = voxelsPerCellFor(map.voxelSize(), config_);
  cell_size_ = factor_ * map.voxelSize();
  grid_cells_ = (grid_voxels_.array() + factor_ - 1) / factor_;
  cap_cells_ = static_cast<int>(std::ceil(config_.max_distance / cell_size_)) + 2;

  last_stamp_ = map.changeCounter();
  seen_blocks_ = map.numBlocks();
  obstacle_.assign(static_cast<size_t>(grid_cells_.prod()), config_.unknown_is_obstacle ? 1 : 0);
  cells_evaluated_ = 0;
  for (const auto& block : map.blocks()) evaluateBlock(map, block->index, nullptr);
  blocks_visited_ = map.numBlocks();
  cells_changed_ = obstacle_.size();

  // DynamicEDT3D takes ownership of the grid and frees it with delete[] per row.
  edt_.reset();  // frees the old transform before the new one is allocated
  const int sx = grid_cells_.x(), sy = grid_cells_.y(), sz = grid_cells_.z();
  bool*** grid = new bool**[sx];
  for (int x = 0; x < sx; ++x) {
    grid[x] = new bool*[sy];
    for (int y = 0; y < sy; ++y) {
      grid[x][y] = new bool[sz];
      for (int z = 0; z < sz; ++z) grid[x][y][z] = obstacle_[linear(Eigen::Vector3i(x, y, z))] != 0;
    }
  }
  edt_ = std::make_unique<Edt>(cap_cells_);
  edt_->initializeMap(sx, sy, sz, grid);
  edt_->update(true);
  nearest_.assign(obstacle_.size(), Nearest());
  syncNearest(Eigen::Vector3i::Zero(), grid_cells_ - Eigen::Vector3i::Ones());
}

void CollisionMap::update(const TsdfMap& map) {
  if (map.numBlocks() < seen_blocks_ || map.gridVoxels() != grid_voxels_) {
    rebuild(map);
    return;
  }
  const uint64_t now = map.changeCounter();
  const std::vector<Eigen::Vector3i> blocks = map.blocksChangedSince(last_stamp_);
  last_stamp_ = now;
  seen_blocks_ = map.numBlocks();
  cells_evaluated_ = 0;
  blocks_visited_ = blocks.size();
  std::vector<Eigen::Vector3i> changed;
  std::vector<Eigen::AlignedBox3i> boxes;  // changed cells of each block
  for (const Eigen::Vector3i& b : blocks) {
    const size_t before = changed.size();
    evaluateBlock(map, b, &changed);
    if (changed.size() == before) continue;
    boxes.emplace_back(changed[before]);
    for (size_t i = before; i < changed.size(); ++i) boxes.back().extend(changed[i]);
  }
  cells_changed_ = changed.size();
  if (changed.empty()) return;
  for (const Eigen::Vector3i& c : changed) {
    if (obstacle_[linear(c)] != 0) {
      edt_->occupyCell(c.x(), c.y(), c.z());
    } else {
      edt_->clearCell(c.x(), c.y(), c.z());
    }
  }
  edt_->update(true);
  // The transform changes only within its cap of a changed cell: copy the
  // union of the dilated boxes, or each box when that is less work.
  const Eigen::Vector3i pad = Eigen::Vector3i::Constant(cap_cells_);
  const auto volume = [&pad](const Eigen::AlignedBox3i& b) {
    return ((b.max() - b.min() + 2 * pad).cast<double>().array() + 1.0).prod();
  };
  Eigen::AlignedBox3i all;
  double separate = 0.0;
  for (const Eigen::AlignedBox3i& b : boxes) {
    all.extend(b);
    separate += volume(b);
  }
  if (volume(all) <= separate) {
    syncNearest(all.min() - pad, all.max() + pad);
  } else {
    for (const Eigen::AlignedBox3i& b : boxes) syncNearest(b.min() - pad, b.max() + pad);
  }
}

CollisionMap::Nearest CollisionMap::nearestFromTransform(const Eigen::Vector3i& cell) const {
  Nearest n;
  Eigen::Vector3i o;
  if (edt_->nearest(cell.x(), cell.y(), cell.z(), &o)) {
    const Eigen::Vector3i d = o - cell;
    n = Nearest{static_cast<int8_t>(d.x()), static_cast<int8_t>(d.y()), static_cast<int8_t>(d.z()), 1};
  }
  return n;
}

void CollisionMap::syncNearest(const Eigen::Vector3i& lo_in, const Eigen::Vector3i& hi_in) {
  const Eigen::Vector3i lo = lo_in.cwiseMax(0);
  const Eigen::Vector3i hi = hi_in.cwiseMin(grid_cells_ - Eigen::Vector3i::Ones());
  Eigen::Vector3i c;
  for (c.x() = lo.x(); c.x() <= hi.x(); ++c.x()) {
    for (c.y() = lo.y(); c.y() <= hi.y(); ++c.y()) {
      for (c.z() = lo.z(); c.z() <= hi.z(); ++c.z()) nearest_[linear(c)] = nearestFromTransform(c);
    }
  }
}

bool CollisionMap::cacheMatchesTransform() const {
  Eigen::Vector3i c;
  for (c.x() = 0; c.x() < grid_cells_.x(); ++c.x()) {
    for (c.y() = 0; c.y() < grid_cells_.y(); ++c.y()) {
      for (c.z() = 0; c.z() < grid_cells_.z(); ++c.z()) {
        const Nearest a = nearest_[linear(c)], b = nearestFromTransform(c);
        if (a.valid != b.valid || (a.valid && (a.dx != b.dx || a.dy != b.dy || a.dz != b.dz))) return false;
      }
    }
  }
  return true;
}

bool CollisionMap::computeObstacle(const TsdfMap& map, const Eigen::Vector3i& cell) const {
  const Eigen::Vector3i lo = cell * factor_;
  const Eigen::Vector3i hi = (lo.array() + factor_).min(grid_voxels_.array());
  Eigen::Vector3i v;
  for (v.z() = lo.z(); v.z() < hi.z(); ++v.z()) {
    for (v.y() = lo.y(); v.y() < hi.y(); ++v.y()) {
      for (v.x() = lo.x(); v.x() < hi.x(); ++v.x()) {
        const TsdfVoxel* voxel = map.voxel(v);
        const VoxelState s = voxel == nullptr ? VoxelState::kUnknown : map.stateOf(*voxel);
        if (s == VoxelState::kOccupied || (s == VoxelState::kUnknown && config_.unknown_is_obstacle)) return true;
      }
    }
  }
  return false;
}

void CollisionMap::evaluateBlock(const TsdfMap& map, const Eigen::Vector3i& block,
                                 std::vector<Eigen::Vector3i>* changed) {
  const Eigen::Vector3i v_lo = block * kBlockSize;
  const Eigen::Vector3i v_hi = (v_lo.array() + kBlockSize).min(grid_voxels_.array()) - 1;
  const Eigen::Vector3i lo = v_lo / factor_, hi = v_hi / factor_;
  Eigen::Vector3i c;
  for (c.z() = lo.z(); c.z() <= hi.z(); ++c.z()) {
    for (c.y() = lo.y(); c.y() <= hi.y(); ++c.y()) {
      for (c.x() = lo.x(); c.x() <= hi.x(); ++c.x()) {
        ++cells_evaluated_;
        const uint8_t obstacle = computeObstacle(map, c) ? 1 : 0;
        uint8_t& held = obstacle_[linear(c)];
        if (obstacle == held) continue;
        held = obstacle;
        if (changed != nullptr) changed->push_back(c);
      }
    }
  }
}

double CollisionMap::distance(const Eigen::Vector3d& p_W) const {
  if (!p_W.allFinite() || (p_W.array() < origin_.array()).any() || (p_W.array() > bounds_max_.array()).any()) {
    return 0.0;
  }
  // In cell units: the nearest obstacles of the 8 cells whose centres
  // surround p (clamped at the grid's faces), the nearest of their cubes.
  const Eigen::Vector3d q = (p_W - origin_) / cell_size_;
  int xs[2], ys[2], zs[2];
  for (int axis = 0; axis < 3; ++axis) {
    int* c = axis == 0 ? xs : (axis == 1 ? ys : zs);
    const int b = static_cast<int>(q[axis] + 0.5) - 1;  // floor(q - 0.5), q >= 0 here
    c[0] = std::clamp(b, 0, grid_cells_[axis] - 1);
    c[1] = std::clamp(b + 1, 0, grid_cells_[axis] - 1);
  }
  const double cap = config_.max_distance / cell_size_;
  double d_sq = cap * cap;
  for (const int x : xs) {
    for (const int y : ys) {
      for (const int z : zs) {
        const Nearest n = nearest_[linear(Eigen::Vector3i(x, y, z))];
        if (!n.valid) continue;
        const double ox = x + n.dx, oy = y + n.dy, oz = z + n.dz;
        const double dx = std::max({ox - q.x(), q.x() - ox - 1.0, 0.0});
        const double dy = std::max({oy - q.y(), q.y() - oy - 1.0, 0.0});
        const double dz = std::max({oz - q.z(), q.z() - oz - 1.0, 0.0});
        d_sq = std::min(d_sq, dx * dx + dy * dy + dz * dz);
      }
    }
  }
  double d = std::sqrt(d_sq) * cell_size_;
  if (config_.bounds_are_obstacle) {
    d = std::min(d, std::min((p_W - origin_).minCoeff(), (bounds_max_ - p_W).minCoeff()));
  }
  return d;
}

bool CollisionMap::isFree(const Eigen::Vector3d& p_W, double radius) const {
  return radius < config_.max_distance && distance(p_W) > radius;
}

bool CollisionMap::isObstacleCell(const Eigen::Vector3i& cell) const {
  if ((cell.array() < 0).any() || (cell.array() >= grid_cells_.array()).any()) return true;
  return obstacle_[linear(cell)] != 0;
}

double CollisionMap::cellCentreDistance(const Eigen::Vector3i& cell) const {
  if ((cell.array() < 0).any() || (cell.array() >= grid_cells_.array()).any()) return 0.0;
  return std::sqrt(static_cast<double>(edt_->sqCells(cell))) * cell_size_;
}

void CollisionMap::clearCells(double clear, std::vector<uint8_t>* mask) const {
  const int sx = grid_cells_.x(), sy = grid_cells_.y(), sz = grid_cells_.z();
  mask->assign(static_cast<size_t>(sx) * sy * sz, 0);
  // cellCentreDistance() >= clear is monotone in the squared cell distance:
  // find the smallest one that passes, with the same arithmetic.
  const auto passes = [&](long long sq) { return std::sqrt(static_cast<double>(sq)) * cell_size_ >= clear; };
  constexpr long long kMaxSq = std::numeric_limits<int>::max();
  if (std::isnan(clear) || !passes(kMaxSq)) return;
  long long min_sq = 0;
  if (!passes(0)) {
    const double r = clear / cell_size_;
    min_sq = std::clamp(static_cast<long long>(std::floor(r * r)) - 2, 0LL, kMaxSq);
    while (!passes(min_sq)) ++min_sq;
    while (min_sq > 0 && passes(min_sq - 1)) --min_sq;
  }
  uint8_t* out = mask->data();
  for (int x = 0; x < sx; ++x) {
    for (int y = 0; y < sy; ++y) {
      const auto* cells = edt_->row(x, y);
      for (int z = 0; z < sz; ++z) *out++ = cells[z].sqdist >= min_sq ? 1 : 0;
    }
  }
}

size_t CollisionMap::memoryBytes() const {
  const size_t rows = static_cast<size_t>(grid_cells_.x()) * static_cast<size_t>(grid_cells_.y());
  constexpr size_t kAllocOverhead = 16;  // per new[] of a row, typical glibc
  return obstacle_.size() * (Edt::kCellBytes + sizeof(uint8_t) + sizeof(Nearest)) +
         2 * rows * (sizeof(void*) + kAllocOverhead);
}

}  // namespace surface_nbv
