#include "surface_nbv/mission/render_ahead.h"

#include <algorithm>
#include <utility>

#include "surface_nbv/sim/scripted_flight.h"

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace surface_nbv {
namespace {

constexpr int kNice = 10;  // the worker's nice value (Linux), against 0 for the mission's threads

}  // namespace

RenderAhead::RenderAhead(const DepthRenderer& renderer, size_t frames, const Transform& T_B_C)
    : renderer_(renderer), frames_(frames), T_B_C_(T_B_C) {}

RenderAhead::~RenderAhead() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void RenderAhead::dropDoneBefore(uint64_t index) {
  for (auto it = slots_.begin(); it != slots_.end();) {
    if (it->done && it->index < index) {
      spare_.push_back(std::move(it->image));
      it = slots_.erase(it);
    } else {
      ++it;
    }
  }
}

std::list<RenderAhead::Slot>::iterator RenderAhead::find(uint64_t index, const Transform& T_W_C) {
  auto it = slots_.begin();
  while (it != slots_.end() && !(it->index == index && it->T_W_C.matrix() == T_W_C.matrix())) ++it;
  return it;
}

void RenderAhead::plan(const TrackerSim& tracker, double next_frame, double frame_dt, uint64_t first_index) {
  if (frames_ == 0) return;
  auto copy = std::make_unique<TrackerSim>(tracker);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++generation_;
    ++stats_.plans;
    dropDoneBefore(first_index);  // frames of an older plan stay: the new one may reach the same poses
    tracker_ = std::move(copy);
    next_frame_ = next_frame;
    frame_dt_ = frame_dt;
    first_index_ = first_index;
    if (!worker_.joinable()) worker_ = std::thread(&RenderAhead::work, this);
  }
  wake_.notify_one();
}

bool RenderAhead::take(uint64_t index, const Transform& T_W_C, DepthImage* image) {
  if (frames_ == 0) return false;
  std::unique_lock<std::mutex> lock(mutex_);
  claimed_ = std::max(claimed_, index + 1);  // the worker no longer starts this frame
  dropDoneBefore(index);
  const auto it = find(index, T_W_C);
  if (it == slots_.end()) return false;
  if (!it->done) {
    ++stats_.waited;
    // Only this thread removes slots, and a list moves none: `it` stays valid.
    rendered_.wait(lock, [&] { return it->done; });
  }
  std::swap(*image, it->image);
  spare_.push_back(std::move(it->image));
  slots_.erase(it);
  ++stats_.taken;
  return true;
}

RenderAheadStats RenderAhead::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

void RenderAhead::work() {
#ifdef __linux__
  // Frames ahead are a guess: they take the cores the mission leaves idle
  // (on Linux a thread has a nice value of its own). Failing to lower it
  // costs nothing but speed, so the result is not checked.
  (void)setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), kNice);
#endif
  std::unique_lock<std::mutex> lock(mutex_);
  uint64_t seen = 0;
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || (generation_ != seen && tracker_ != nullptr); });
    if (stop_) return;
    seen = generation_;
    const std::unique_ptr<TrackerSim> tracker = std::move(tracker_);
    double t = next_frame_;
    const double dt = frame_dt_;
    uint64_t index = first_index_;
    for (size_t j = 0; j < frames_; ++j, ++index) {
      lock.unlock();
      // The mission's own stepping (mission_runner.cpp), so the poses agree bit for bit.
      while (tracker->time() + 1e-9 < t) tracker->step();
      t += dt;
      const UavState& s = tracker->state();
      const Transform T_W_C = levelBodyPose(s.p_W, s.yaw) * T_B_C_;
      lock.lock();
      if (stop_ || generation_ != seen) break;
      // Skip a frame the mission has passed or an earlier plan rendered at this pose.
      if (index < claimed_ || find(index, T_W_C) != slots_.end()) continue;
      DepthImage image;
      if (!spare_.empty()) {
        image = std::move(spare_.back());
        spare_.pop_back();
      }
      const auto slot = slots_.insert(slots_.end(), Slot{index, T_W_C, false, DepthImage()});
      lock.unlock();
      renderer_.render(T_W_C, &image, index);
      lock.lock();
      ++stats_.rendered;
      slot->image = std::move(image);
      slot->done = true;
      rendered_.notify_all();
    }
  }
}

}  // namespace surface_nbv
