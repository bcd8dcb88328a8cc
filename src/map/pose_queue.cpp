#include "surface_nbv/map/pose_queue.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace surface_nbv {

Status PoseQueueConfig::validate() const {
  if (capacity < 2) return Status::Error("capacity expected >= 2");
  if (!std::isfinite(max_interval) || max_interval <= 0.0) return Status::Error("max_interval expected > 0");
  if (!std::isfinite(reset_tolerance) || reset_tolerance < 0.0) {
    return Status::Error("reset_tolerance expected >= 0");
  }
  return Status::Ok();
}

const char* toString(PoseLookup result) {
  switch (result) {
    case PoseLookup::kFound: return "found";
    case PoseLookup::kNotYet: return "not_yet";
    case PoseLookup::kTooOld: return "too_old";
    case PoseLookup::kGap: return "gap";
  }
  return "unknown";
}

PoseQueue::PoseQueue(const PoseQueueConfig& config) : config_(config) {}

Status PoseQueue::add(double stamp, const Transform& T_W_S) {
  if (!std::isfinite(stamp)) return Status::Error("pose stamp is not finite");
  const Eigen::Matrix3d R = T_W_S.linear();
  if (!T_W_S.translation().allFinite() || !R.allFinite()) return Status::Error("pose has non-finite values");
  if (!(R.transpose() * R).isIdentity(1e-6) || R.determinant() < 0.0) {
    return Status::Error("pose rotation is not orthonormal with determinant 1");
  }
  if (!poses_.empty() && stamp < newest() - config_.reset_tolerance) {
    poses_.clear();
    ++resets_;
  }
  const StampedPose pose{stamp, T_W_S.translation(), Eigen::Quaterniond(R).normalized()};
  const auto at = std::lower_bound(poses_.begin(), poses_.end(), stamp,
                                   [](const StampedPose& p, double s) { return p.stamp < s; });
  if (at != poses_.end() && at->stamp == stamp) {
    *at = pose;
  } else {
    poses_.insert(at, pose);
  }
  while (poses_.size() > config_.capacity) poses_.pop_front();
  return Status::Ok();
}

PoseLookup PoseQueue::lookup(double stamp, Transform* T_W_S) const {
  if (!std::isfinite(stamp)) return PoseLookup::kTooOld;
  if (poses_.empty() || stamp > newest()) return PoseLookup::kNotYet;
  if (stamp < oldest()) return PoseLookup::kTooOld;
  const auto after = std::lower_bound(poses_.begin(), poses_.end(), stamp,
                                      [](const StampedPose& p, double s) { return p.stamp < s; });
  Eigen::Vector3d t = after->t_W_S;
  Eigen::Quaterniond q = after->q_W_S;
  if (after->stamp != stamp) {
    const StampedPose& before = *std::prev(after);
    const double span = after->stamp - before.stamp;
    if (span > config_.max_interval) return PoseLookup::kGap;
    const double alpha = (stamp - before.stamp) / span;
    t = (1.0 - alpha) * before.t_W_S + alpha * after->t_W_S;
    q = before.q_W_S.slerp(alpha, after->q_W_S);
  }
  *T_W_S = Transform::Identity();
  T_W_S->linear() = q.toRotationMatrix();
  T_W_S->translation() = t;
  return PoseLookup::kFound;
}

}  // namespace surface_nbv
