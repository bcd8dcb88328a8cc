#include "surface_nbv/ros/stats_reporter.h"

#include <algorithm>

#include "surface_nbv/NodeStats.h"

namespace surface_nbv {

StatsReporter::StatsReporter(ros::NodeHandle& nh, const std::string& topic, const std::string& node_name,
                             double period_s)
    : node_name_(node_name) {
  pub_ = nh.advertise<surface_nbv::NodeStats>(topic, 1, true);
  timer_ = nh.createWallTimer(ros::WallDuration(period_s), &StatsReporter::onTimer, this);
}

void StatsReporter::count(const std::string& name, uint64_t n) {
  std::lock_guard<std::mutex> lock(mutex_);
  counters_[name] += n;
}

void StatsReporter::set(const std::string& name, uint64_t value) {
  std::lock_guard<std::mutex> lock(mutex_);
  counters_[name] = value;
}

void StatsReporter::recordMs(double ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  times_ms_.push_back(ms);
}

uint64_t StatsReporter::get(const std::string& name) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = counters_.find(name);
  return it == counters_.end() ? 0 : it->second;
}

void StatsReporter::onTimer(const ros::WallTimerEvent&) { publishNow(); }

void StatsReporter::publishNow() {
  surface_nbv::NodeStats msg;
  msg.header.stamp = ros::Time::now();
  msg.node = node_name_;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& kv : counters_) {
      surface_nbv::Counter c;
      c.name = kv.first;
      c.count = kv.second;
      msg.counters.push_back(c);
    }
    if (!times_ms_.empty()) {
      std::nth_element(times_ms_.begin(), times_ms_.begin() + times_ms_.size() / 2, times_ms_.end());
      msg.median_processing_ms = times_ms_[times_ms_.size() / 2];
      msg.max_processing_ms = *std::max_element(times_ms_.begin(), times_ms_.end());
      times_ms_.clear();
    }
  }
  pub_.publish(msg);
}

}  // namespace surface_nbv
