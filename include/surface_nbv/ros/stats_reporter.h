// Named event counters and processing times of a node, published as
// surface_nbv/NodeStats on `topic` (relative to `nh`) every period. Every dropped input is
// counted here under its reason, so drops are visible, never silent.
// Thread safety: all methods may be called from any callback thread.
#pragma once

#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>

namespace surface_nbv {

class StatsReporter {
 public:
  StatsReporter(ros::NodeHandle& nh, const std::string& topic, const std::string& node_name, double period_s);

  void count(const std::string& name, uint64_t n = 1);
  // Sets a gauge (a value that goes up and down, e.g. blocks in the map).
  void set(const std::string& name, uint64_t value);
  void recordMs(double ms);
  uint64_t get(const std::string& name) const;
  void publishNow();

 private:
  void onTimer(const ros::WallTimerEvent&);

  std::string node_name_;
  ros::Publisher pub_;
  ros::WallTimer timer_;
  mutable std::mutex mutex_;
  std::map<std::string, uint64_t> counters_;
  std::vector<double> times_ms_;
};

}  // namespace surface_nbv
