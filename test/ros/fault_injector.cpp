// Test helper node for mission_faults.test: relays depth/image to
// depth/image_lossy dropping a seeded fraction of the frames, and kills
// (SIGKILL) the processes of the named nodes at seeded random ROS times, one
// after the other, so roslaunch respawns them. Counts what it did on stdout.
//   ~drop_fraction (0.3), ~seed (1), ~kill_nodes ([tsdf_mapper, nbv_planner]),
//   ~kill_after ([20, 60]: the window of ROS time after the first frame, s)
#include <signal.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/Image.h>

namespace {

// True when process `pid` was started with ROS_MASTER_URI=`master` in its
// environment (false when /proc/PID/environ cannot be read).
bool sameMaster(int pid, const std::string& master) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/environ", std::ios::binary);
  const std::string wanted = "ROS_MASTER_URI=" + master;
  std::string entry;
  while (std::getline(in, entry, '\0')) {
    if (entry.rfind("ROS_MASTER_URI=", 0) == 0) return entry == wanted;
  }
  return false;
}

// Pids of the processes started with __name:=NAME (roslaunch passes it) under
// this process's ROS master (same ROS_MASTER_URI), so that concurrent rostest
// runs on the machine do not kill each other's nodes.
std::vector<int> pidsOf(const std::string& name) {
  std::vector<int> pids;
  const char* master = std::getenv("ROS_MASTER_URI");
  if (master == nullptr) return pids;
  const std::string command = "pgrep -f -- '__name:=" + name + "( |$)'";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return pids;
  int pid = 0;
  while (std::fscanf(pipe, "%d", &pid) == 1) {
    if (sameMaster(pid, master)) pids.push_back(pid);
  }
  pclose(pipe);
  return pids;
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "fault_injector");
  ros::NodeHandle nh, priv("~");
  double drop_fraction = 0.3;
  int seed = 1;
  std::vector<std::string> kill_nodes{"tsdf_mapper", "nbv_planner"};
  std::vector<double> window{20.0, 60.0};
  priv.getParam("drop_fraction", drop_fraction);
  priv.getParam("seed", seed);
  priv.getParam("kill_nodes", kill_nodes);
  priv.getParam("kill_after", window);
  if (window.size() != 2 || !(window[0] >= 0.0) || !(window[1] >= window[0])) {
    ROS_FATAL("fault_injector: ~kill_after expected [start, end] with 0 <= start <= end");
    return 2;
  }
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> kill_times;
  for (size_t i = 0; i < kill_nodes.size(); ++i) kill_times.push_back(window[0] + uniform(rng) * (window[1] - window[0]));
  std::sort(kill_times.begin(), kill_times.end());

  ros::Publisher out = nh.advertise<sensor_msgs::Image>("depth/image_lossy", 5);
  size_t relayed = 0, dropped = 0, next_kill = 0;
  ros::Time first;
  ros::Subscriber in = nh.subscribe<sensor_msgs::Image>("depth/image", 5, [&](const sensor_msgs::ImageConstPtr& m) {
    if (first.isZero()) first = m->header.stamp;
    if (uniform(rng) < drop_fraction) {
      ++dropped;
    } else {
      out.publish(m);
      ++relayed;
    }
    if (next_kill < kill_nodes.size() && (m->header.stamp - first).toSec() >= kill_times[next_kill]) {
      const std::string& name = kill_nodes[next_kill];
      const std::vector<int> pids = pidsOf(name);
      for (int pid : pids) kill(pid, SIGKILL);
      ROS_WARN("fault_injector: SIGKILL to %s (%zu process(es)) at %.1f s; frames relayed %zu, dropped %zu",
               name.c_str(), pids.size(), (m->header.stamp - first).toSec(), relayed, dropped);
      ++next_kill;
    }
  });
  ros::spin();
  std::printf("fault_injector: relayed %zu, dropped %zu, kills %zu\n", relayed, dropped, next_kill);
  return 0;
}
