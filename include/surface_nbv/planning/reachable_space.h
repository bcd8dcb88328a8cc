// The part of a CollisionMap's free space connected to a point: a flood
// fill over the cells (6-connected) whose centre is at least radius - slack
// from the nearest obstacle. With slack = half a cell diagonal it is a
// superset of what the path planner can reach (any point it accepts, with
// clearance > radius, lies in such a cell, and a collision-free path only
// crosses such cells); with slack 0 (the explorer's choice) it leaves out
// passages within a few centimetres of the planner's limit, which the PRM
// rarely finds within its budget anyway, and so it tells at once that a
// target behind them is not worth the planner's iteration budget. The
// explorer fills once per map version, before the first leg it plans.
//
// Clear::kPlannerTest judges each cell by the path planner's own test at its
// centre instead, CollisionMap::isFree(centre, radius - slack): the distance
// to the obstacle cubes rather than their centres (about half a cell
// stricter) and to the bounds' faces. A query per cell, slower; the oracle
// (mission/oracle_planner.h) fills this way, so that the viewpoints it keeps
// in narrow passages are ones the planner can fly to.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/common.h"
#include "surface_nbv/map/collision_map.h"

namespace surface_nbv {

class ReachableSpace {
 public:
  enum class Clear {
    kCentreDistance,  // cellCentreDistance() >= radius - slack, in one pass over the transform (the explorer's)
    kPlannerTest,     // CollisionMap::isFree(centre, radius - slack)
  };

  // Fills from the cell of `from` (or, if that cell is not clear, from the
  // clear cells within `seed_radius` of it). `bounds` are the map's: cell
  // (i, j, k) covers bounds.min + cellSize * [i, i + 1) and so on. Without a
  // clear seed cell nothing is known: reachable() then answers true.
  void fill(const CollisionMap& map, const AlignedBox& bounds, const Eigen::Vector3d& from, double radius,
            double slack = 0.0, double seed_radius = 2.0, Clear clear = Clear::kCentreDistance);
  // Whether p's cell, or one of its 6 neighbours, was filled (true when the
  // last fill found no seed; false outside the grid).
  bool reachable(const Eigen::Vector3d& p) const;
  // Whether the last fill reached this cell (false outside the grid).
  bool filled(const Eigen::Vector3i& cell) const;
  // A shortest 6-connected way through the filled cells from a seed cell to
  // `to`'s cell (or its filled 6-neighbour): the cell centres, seed first.
  // False (and empty) when `to` is not reachable() or nothing was seeded.
  // A guide, not a path: a centre may be closer to an obstacle than the
  // planner accepts (the fill's test is its own, see above).
  bool corridor(const Eigen::Vector3d& to, std::vector<Eigen::Vector3d>* points) const;
  // Cells filled by the last fill.
  size_t size() const { return filled_; }
  bool seeded() const { return seeded_; }

 private:
  bool cellOf(const Eigen::Vector3d& p, Eigen::Vector3i* cell) const;
  // p's cell if filled, else its first filled 6-neighbour (in `cell`); false if neither.
  bool filledAt(const Eigen::Vector3d& p, Eigen::Vector3i* cell) const;
  // The order of CollisionMap::clearCells: z fastest.
  size_t index(const Eigen::Vector3i& c) const {
    return (static_cast<size_t>(c.x()) * static_cast<size_t>(cells_.y()) + static_cast<size_t>(c.y())) *
               static_cast<size_t>(cells_.z()) +
           static_cast<size_t>(c.z());
  }
  // 0: not clear. A filled cell holds kFilled + the direction (0 to 5: +x,
  // -x, +y, -y, +z, -z) to the cell it was reached from, or kSeed.
  static constexpr uint8_t kOpen = 1, kFilled = 2, kSeed = kFilled + 6;

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3i cells_ = Eigen::Vector3i::Zero();
  double cell_ = 1.0;
  std::vector<uint8_t> state_;  // per cell: 0, kOpen, kFilled + direction or kSeed
  size_t filled_ = 0;
  bool seeded_ = false;
};

}  // namespace surface_nbv
