#include "surface_nbv/map/collision_map.h"

#include <algorithm>
#include <cmath>

#include <dynamicEDT3D/dynamicEDT3D.h>

namespace surface_nbv {

// DynamicEDT3D keeps its cells protected; this reads them without the
// library's out-of-line, bounds-checked accessors (the caller checks).
class CollisionMap::Edt : public DynamicEDT3D {
 public:
  explicit Edt(int max_sq_cells) : DynamicEDT3D(max_sq_cells) {}

  int sqCells(const Eigen::Vector3i& c) const { return data[c.x()][c.y()][c.z()].sqdist; }
  // The nearest obstacle cell, false when none is within the cap.
  bool nearest(const Eigen::Vector3i& c, Eigen::Vector3i* obstacle) const {
    const dataCell& d = data[c.x()][c.y()][c.z()];
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
  if (config.min_cell_size <= voxel_size) return 1;
  return static_cast<int>(std::ceil(config.min_cell_size / voxel_size - 1e-9));
}

CollisionMap::CollisionMap(const TsdfMap& map, const CollisionConfig& config) : config_(config) { rebuild(map); }

CollisionMap::~CollisionMap() = default;

void CollisionMap::rebuild(const TsdfMap& map) {
  origin_ = map.config().bounds.min;
  bounds_max_ = map.config().bounds.max;
  grid_voxels_ = map.gridVoxels();
  factor_ = voxelsPerCellFor(map.voxelSize(), config_);
  cell_size_ = factor_ * map.voxelSize();
  grid_cells_ = (grid_voxels_.array() + factor_ - 1) / factor_;
  const int cap_cells = static_cast<int>(std::ceil(config_.max_distance / cell_size_)) + 2;
  max_sq_cells_ = cap_cells * cap_cells;

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
  edt_ = std::make_unique<Edt>(max_sq_cells_);
  edt_->initializeMap(sx, sy, sz, grid);
  edt_->update(true);
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
  for (const Eigen::Vector3i& b : blocks) evaluateBlock(map, b, &changed);
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
  const Eigen::Vector3d f = (p_W - origin_) / cell_size_;
  double d = config_.max_distance;
  const int mode = getenv("MODE") ? atoi(getenv("MODE")) : 0;
  Eigen::Vector3i base, span;
  if (mode == 0) { base = f.array().floor().cast<int>(); span.setConstant(1); }
  else if (mode == 1) { base = (f.array() - 0.5).floor().cast<int>(); span.setConstant(2); }
  else { base = (f.array() - 1.0).floor().cast<int>(); span.setConstant(3); }
  for (int dz = 0; dz < span.z(); ++dz) for (int dy = 0; dy < span.y(); ++dy) for (int dx = 0; dx < span.x(); ++dx) {
    const Eigen::Vector3i cell = (base + Eigen::Vector3i(dx, dy, dz)).array().max(0).min(grid_cells_.array() - 1).matrix();
    Eigen::Vector3i o;
    if (edt_->nearest(cell, &o)) {
      const Eigen::Vector3d lo = origin_ + o.cast<double>() * cell_size_;
      const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(cell_size_);
      d = std::min(d, (lo - p_W).cwiseMax(p_W - hi).cwiseMax(0.0).norm());
    }
  }
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

size_t CollisionMap::memoryBytes() const {
  const size_t rows = static_cast<size_t>(grid_cells_.x()) * static_cast<size_t>(grid_cells_.y());
  constexpr size_t kAllocOverhead = 16;  // per new[] of a row, typical glibc
  return obstacle_.size() * (Edt::kCellBytes + sizeof(uint8_t)) + 2 * rows * (sizeof(void*) + kAllocOverhead);
}

}  // namespace surface_nbv
