// A bounded, time-ordered queue of stamped sensor poses T_W_S that answers
// "the pose at time t" by interpolating between the two poses around t
// (linear in translation, slerp in rotation). It never extrapolates and never
// falls back to the latest pose: a frame is integrated with the pose it was
// taken at, or not at all.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>

#include "surface_nbv/common.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct PoseQueueConfig {
  size_t capacity = 2000;        // poses kept; the oldest go first (20 s of 100 Hz TF)
  double max_interval = 0.5;     // s: two poses further apart do not bracket a stamp (a stalled stream)
  double reset_tolerance = 1.0;  // s: a pose older than the newest by more empties the queue (a bag restarted)

  // Names the first bad key, e.g. "capacity expected >= 2".
  Status validate() const;
};

enum class PoseLookup {
  kFound,    // the pose at t, interpolated between its neighbours (or exact)
  kNotYet,   // t is newer than the newest pose, or the queue is empty: ask again later
  kTooOld,   // t is older than the oldest pose kept, or not finite: drop the frame
  kGap,      // the poses around t are more than max_interval apart: drop the frame
};

const char* toString(PoseLookup result);

// Stamps are seconds on any clock, as long as one queue sees one clock.
// Poses are added in any order: each goes to its place by stamp, and one with
// the stamp of a pose already kept replaces it. A pose older than the newest
// by more than reset_tolerance means the clock jumped back (a bag or a
// simulation restarted): the queue empties and starts over from that pose
// instead of answering kTooOld forever. Not thread-safe.
class PoseQueue {
 public:
  // `config` must validate(); the constructor trusts it.
  explicit PoseQueue(const PoseQueueConfig& config = PoseQueueConfig());

  // Refuses (and keeps nothing of) a non-finite stamp or pose, or a linear
  // part that is not a rotation within 1e-6.
  Status add(double stamp, const Transform& T_W_S);
  // Fills *T_W_S only when the answer is kFound.
  PoseLookup lookup(double stamp, Transform* T_W_S) const;

  void clear() { poses_.clear(); }
  bool empty() const { return poses_.empty(); }
  size_t size() const { return poses_.size(); }
  // Stamps of the oldest and newest poses kept; the queue must not be empty.
  double oldest() const { return poses_.front().stamp; }
  double newest() const { return poses_.back().stamp; }
  // Times the clock jumped back and emptied the queue.
  uint64_t resets() const { return resets_; }
  const PoseQueueConfig& config() const { return config_; }

 private:
  struct StampedPose {
    double stamp;
    Eigen::Vector3d t_W_S;
    Eigen::Quaterniond q_W_S;
  };

  PoseQueueConfig config_;
  std::deque<StampedPose> poses_;
  uint64_t resets_ = 0;
};

}  // namespace surface_nbv
