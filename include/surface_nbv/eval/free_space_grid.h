// Where a sensor can be around a structure: the cells of a regular grid over
// `bounds` whose centre lies at least `collision_radius` from every triangle
// and that connect (through 6-neighbours) to a side or the top of the grid,
// the way in from outside. The bottom face is the floor, not a way in, so the
// inside of a closed building is never reached. Read-only once built: queries
// are thread safe.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "surface_nbv/common.h"
#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

class FreeSpaceGrid {
 public:
  // Refuses empty bounds, a cell <= 0 and grids above 64M cells.
  Status build(const TriangleMesh& mesh, const AlignedBox& bounds, double cell, double collision_radius,
               int threads = 1);

  // True if p lies in a reachable collision-free cell (false outside the grid).
  bool reachable(const Eigen::Vector3d& p) const;
  // Chebyshev distance in cells from p's cell to the nearest reachable cell:
  // 0 in one, at most 255, -1 outside the grid. Every point of a reachable
  // cell lies at least (k - 1) cells from p, so a search along a ray may skip that far.
  int cellsToReachable(const Eigen::Vector3d& p) const;
  double cellSize() const { return cell_; }
  const AlignedBox& bounds() const { return bounds_; }
  const Eigen::Vector3i& dims() const { return dims_; }
  size_t numCells() const { return state_.size(); }
  size_t numBlocked() const { return blocked_; }
  size_t numReachable() const { return reachable_; }

 private:
  enum : uint8_t { kFree = 0, kBlocked = 1, kReachable = 2 };
  size_t linear(int x, int y, int z) const {
    return static_cast<size_t>(x) +
           static_cast<size_t>(dims_.x()) * (static_cast<size_t>(y) + static_cast<size_t>(dims_.y()) * z);
  }
  void markBlocked(const TriangleMesh& mesh, double collision_radius, int threads);
  void floodFromOutside();
  // Chebyshev distance in cells to the nearest reachable cell, capped at 255.
  void measureClearance();
  // Cell of p, or false outside the grid.
  bool cellOf(const Eigen::Vector3d& p, Eigen::Vector3i* cell) const;

  AlignedBox bounds_;
  double cell_ = 1.0;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  std::vector<uint8_t> state_;
  std::vector<uint8_t> clearance_;  // cells to the nearest reachable one
  size_t blocked_ = 0, reachable_ = 0;
};

// Squared distance from p to triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5).
double squaredDistanceToTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c);

}  // namespace surface_nbv
