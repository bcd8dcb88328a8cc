#include "surface_nbv/surface/viewpoint_merger.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "surface_nbv/surface/point_grid.h"

namespace surface_nbv {
bool ViewpointMerger::mergeable(const Viewpoint& a, const Viewpoint& b) const {
  const double d = (a.position - b.position).norm();
  if (d < config_.epsilon) return true;
  return d < config_.parallel_distance && a.view_direction.dot(b.view_direction) >= config_.parallel_cos;
}

std::vector<Viewpoint> ViewpointMerger::merge(const std::vector<Viewpoint>& poses, const CollisionMap& collision,
                                              const AlignedBox& bounds, std::vector<int>* group_of) const {
  AlignedBox box;
  for (const Viewpoint& q : poses) box.extend(q.position);
  PointGrid seeds(box, std::max(config_.epsilon, config_.parallel_distance), poses.size());  // group ids at their seeds
  std::vector<int> seed_pose;  // group -> its seed pose
  std::vector<Eigen::Vector3d> position_sum, direction_sum;
  std::vector<std::vector<uint32_t>> sources;
  std::vector<size_t> count;
  if (group_of != nullptr) group_of->assign(poses.size(), -1);

  for (size_t i = 0; i < poses.size(); ++i) {
    const Viewpoint& q = poses[i];
    int best = -1;
    seeds.forEachNear(q.position, [&](int g) {
      if ((best < 0 || g < best) && mergeable(poses[seed_pose[g]], q)) best = g;
    });
    if (best < 0) {
      best = static_cast<int>(seed_pose.size());
      seed_pose.push_back(static_cast<int>(i));
      position_sum.push_back(Eigen::Vector3d::Zero());
      direction_sum.push_back(Eigen::Vector3d::Zero());
      sources.emplace_back();
      count.push_back(0);
      seeds.insert(best, q.position);
    }
    ++count[best];
    position_sum[best] += q.position;
    direction_sum[best] += q.view_direction;
    sources[best].insert(sources[best].end(), q.sources.begin(), q.sources.end());
    if (group_of != nullptr) (*group_of)[i] = best;
  }

  std::vector<Viewpoint> out(seed_pose.size());
  for (size_t g = 0; g < out.size(); ++g) {
    const Viewpoint& seed = poses[seed_pose[g]];
    Viewpoint& v = out[g];
    v.sources = std::move(sources[g]);
    std::sort(v.sources.begin(), v.sources.end());
    const Eigen::Vector3d mean = position_sum[g] / static_cast<double>(count[g]);
    const Eigen::Vector3d dir = direction_sum[g];
    const bool mean_ok = count[g] > 1 && std::hypot(dir.x(), dir.y()) > 1e-6 * dir.norm() &&
                         dir.norm() > 1e-9 && bounds.contains(mean) &&
                         collision.isFree(mean, config_.collision_radius);
    if (mean_ok) {
      v.position = mean;
      v.view_direction = dir.normalized();
      v.yaw = std::atan2(dir.y(), dir.x());
    } else {
      v.position = seed.position;
      v.view_direction = seed.view_direction;
      v.yaw = seed.yaw;
    }
  }
  return out;
}

}  // namespace surface_nbv
