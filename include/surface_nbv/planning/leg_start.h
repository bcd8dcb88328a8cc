// A leg decided from the UAV's pose at the start of a decision, sent after
// the UAV flew on: where the leg should start instead.
//
// A decision that replaces the leg being flown (a covered target, new ISEs
// in front of it, an obstacle) takes wall time while the UAV keeps flying
// its old leg; at 4x a second of planning is 2 m of flight, and the tracker
// refuses a trajectory whose first point lies farther than its start limit
// (mpc_tracker's max_start_distance, 2 m) and holds instead. restartLeg joins
// the UAV's pose now to the leg by a straight segment that keeps `clearance`
// from the obstacles of `map` (unknown space included, as for the planner's
// own paths), to the farthest point of the leg's first `reach` metres that
// such a segment reaches, else to the leg's first point.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "surface_nbv/map/collision_map.h"

namespace surface_nbv {

enum class LegStart {
  kUnchanged,  // the UAV is still within `tolerance` of the leg's first point
  kJoined,     // the leg now starts at the UAV (joined to one of its points)
  kBlocked,    // no straight segment from the UAV to the leg keeps the clearance: the leg as it was
};

const char* toString(LegStart start);

// `leg`: [x, y, z, yaw] points, the first the pose the leg was planned from.
// On kJoined, `leg` becomes {now, leg[k], leg[k + 1], ...}.
LegStart restartLeg(const Eigen::Vector4d& now, const CollisionMap& map, double clearance, double reach,
                    double tolerance, std::vector<Eigen::Vector4d>* leg);

// Whether every point of the straight segment a-b, sampled every half cell
// of `map`, keeps `clearance` from its obstacles.
bool segmentClear(const CollisionMap& map, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double clearance);

}  // namespace surface_nbv
