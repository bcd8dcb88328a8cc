#include "surface_nbv/planning/leg_start.h"

#include <algorithm>
#include <cmath>

namespace surface_nbv {

const char* toString(LegStart start) {
  switch (start) {
    case LegStart::kUnchanged: return "unchanged";
    case LegStart::kJoined: return "joined";
    case LegStart::kBlocked: return "blocked";
  }
  return "unknown";
}

bool segmentClear(const CollisionMap& map, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double clearance) {
  const double length = (b - a).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / (0.5 * map.cellSize()))));
  for (int i = 0; i <= steps; ++i) {
    if (!map.isFree(a + (b - a) * (static_cast<double>(i) / steps), clearance)) return false;
  }
  return true;
}

LegStart restartLeg(const Eigen::Vector4d& now, const CollisionMap& map, double clearance, double reach,
                    double tolerance, std::vector<Eigen::Vector4d>* leg) {
  std::vector<Eigen::Vector4d>& p = *leg;
  if (p.empty() || (now.head<3>() - p.front().head<3>()).norm() <= tolerance) return LegStart::kUnchanged;
  // Points within `reach` along the leg, from its start.
  size_t last = 0;
  double along = 0.0;
  while (last + 1 < p.size()) {
    along += (p[last + 1].head<3>() - p[last].head<3>()).norm();
    if (along > reach) break;
    ++last;
  }
  for (size_t k = last + 1; k-- > 0;) {
    if (!segmentClear(map, now.head<3>(), p[k].head<3>(), clearance)) continue;
    std::vector<Eigen::Vector4d> joined{now};
    joined.insert(joined.end(), p.begin() + static_cast<long>(k), p.end());
    p = std::move(joined);
    return LegStart::kJoined;
  }
  return LegStart::kBlocked;
}

}  // namespace surface_nbv
