// Renders a simulated flight's next depth frames on a thread of its own
// while the mission plans. The poses of the frames to come are those of a
// copy of the tracker that keeps its trajectory, stepped to the frame times
// as the mission steps the real one; a frame is handed over only when its
// index and its pose equal the ones the mission asks for, bit for bit, so
// an image taken from here is the one rendering it in line would give, and a
// new trajectory only wastes the frames rendered for the old one.
//
// The mission calls plan() when it stops to plan (the decision may keep the
// trajectory: 65 % of them did on the power plant) and again after it sets a
// new one, and take() at every frame, rendering the frame itself when this
// returns false. A frame the worker has not started is claimed by take() and
// skipped by the worker, so the two render different frames side by side;
// a frame an earlier plan rendered at the same pose is not rendered again.
// Thread safety: one caller thread; the worker is internal.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <list>
#include <memory>
#include <mutex>
#include <thread>

#include "surface_nbv/common.h"
#include "surface_nbv/sim/depth_image.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/tracking/tracker_sim.h"

namespace surface_nbv {

struct RenderAheadStats {
  uint64_t plans = 0;     // plan() calls
  uint64_t rendered = 0;  // frames the worker rendered
  uint64_t taken = 0;     // of those, handed over by take()
  uint64_t waited = 0;    // take() calls that waited for the worker's frame in progress
};

class RenderAhead {
 public:
  // `renderer` (its own thread count is used) must outlive this object.
  // `frames`: how many frames past the plan's first the worker renders; 0
  // disables it (take() always returns false). T_B_C: the camera mount.
  RenderAhead(const DepthRenderer& renderer, size_t frames, const Transform& T_B_C);
  ~RenderAhead();
  RenderAhead(const RenderAhead&) = delete;
  RenderAhead& operator=(const RenderAhead&) = delete;

  // Replaces the plan (frames rendered for the old one are kept while they
  // may still be asked for) with `frames` frames: the first of index `first_index` at
  // flight time `next_frame`, one every `frame_dt`, at the poses `tracker`
  // reaches when stepped as MissionRunner steps it
  // (`while (time() + 1e-9 < t) step();` then `t += frame_dt`).
  void plan(const TrackerSim& tracker, double next_frame, double frame_dt, uint64_t first_index);
  // Moves frame `index` rendered at exactly T_W_C into *image and returns
  // true, waiting for the worker if it is rendering it; false when it was not
  // planned at that pose (the caller renders it; the worker will skip it).
  bool take(uint64_t index, const Transform& T_W_C, DepthImage* image);

  RenderAheadStats stats() const;

 private:
  struct Slot {
    uint64_t index = 0;
    Transform T_W_C = Transform::Identity();
    bool done = false;
    DepthImage image;
  };
  void work();
  // Frames rendered before `index` are of no more use (mutex_ held).
  void dropDoneBefore(uint64_t index);
  // The slot of frame `index` at exactly T_W_C, or end() (mutex_ held).
  std::list<Slot>::iterator find(uint64_t index, const Transform& T_W_C);

  const DepthRenderer& renderer_;
  const size_t frames_;
  const Transform T_B_C_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;      // a new plan, or stop
  std::condition_variable rendered_;  // a slot is done
  std::unique_ptr<TrackerSim> tracker_;  // the plan's tracker, moved to the worker when it starts the plan
  double next_frame_ = 0.0, frame_dt_ = 0.0;
  uint64_t first_index_ = 0;
  uint64_t generation_ = 0;  // plan() count: the worker drops a plan that is no longer the latest
  uint64_t claimed_ = 0;     // take() has passed every index below this
  std::list<Slot> slots_;    // frames rendered or in progress, of this plan and earlier ones
  std::deque<DepthImage> spare_;
  RenderAheadStats stats_;
  bool stop_ = false;
  std::thread worker_;
};

}  // namespace surface_nbv
