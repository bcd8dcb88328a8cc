// A recorded mission replayed through launch/map_bag.launch rebuilds the
// live map (issue #8), and replaying the same bag twice gives the same map
// (issue #9). Phase 1 runs on rostest's master (mission_replay.test): the box
// mission flies with the real nodes while this node records depth/image,
// depth/camera_info, /tf, /tf_static and /clock into a bag (rosbag C++ API)
// and relays each recorded image to the live mapper on depth/image_recorded,
// so the live mapper is offered exactly the frames of the bag. When the
// mission is done the live map is saved through tsdf_mapper/save_map. Phase
// 2 starts map_bag.launch twice with roslaunch on a master of its own (the
// mission's /clock would fight the player's), waits for the player to end,
// saves each map through save_map and stops the launch. The test then loads
// the three files and compares known voxels (w >= W_th), their signs and the
// digests of the two replays.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>
#include <tf2_msgs/TFMessage.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include "../fuzz/map_digest.h"
#include "surface_nbv/FilePath.h"
#include "surface_nbv/NodeStats.h"
#include "surface_nbv/PlannerStatus.h"
#include "surface_nbv/map/map_io.h"
#include "surface_nbv/ros/mapper_params.h"

using namespace surface_nbv;

namespace {

// Records the sensor stream into a bag and relays the recorded images. Bag
// times are the messages' own stamps (the clock's value for /clock), so the
// player's --clock and the recorded /clock never disagree. Images are taken
// only once a camera_info, the static transforms and a /tf older than the
// image are in the bag, so the replayed mapper can fuse every one of them.
class StreamRecorder {
 public:
  StreamRecorder(ros::NodeHandle& nh, const std::string& bag_path) : bag_(bag_path, rosbag::bagmode::Write) {
    bag_.setCompression(rosbag::compression::LZ4);
    relay_ = nh.advertise<sensor_msgs::Image>("depth/image_recorded", 20);
    subs_.push_back(nh.subscribe("depth/image", 20, &StreamRecorder::onImage, this));
    subs_.push_back(nh.subscribe("depth/camera_info", 20, &StreamRecorder::onInfo, this));
    subs_.push_back(nh.subscribe("/tf", 500, &StreamRecorder::onTf, this));
    subs_.push_back(nh.subscribe("/tf_static", 10, &StreamRecorder::onTfStatic, this));
    subs_.push_back(nh.subscribe("/clock", 1000, &StreamRecorder::onClock, this));
  }

  // No more images (nor camera_info); /tf and /clock go on until close(), so
  // the last images keep the transforms after their stamp.
  void stopImages() {
    std::lock_guard<std::mutex> l(mutex_);
    images_stopped_ = true;
  }
  // Unsubscribing waits for running callbacks, so it must not hold the mutex.
  void close() {
    {
      std::lock_guard<std::mutex> l(mutex_);
      closed_ = true;
    }
    subs_.clear();
    std::lock_guard<std::mutex> l(mutex_);
    bag_.close();
  }
  size_t images() const {
    std::lock_guard<std::mutex> l(mutex_);
    return images_;
  }

 private:
  void onImage(const sensor_msgs::ImageConstPtr& msg) {
    std::lock_guard<std::mutex> l(mutex_);
    if (closed_ || images_stopped_) return;
    if (!armed_) {
      if (!info_ || statics_.empty() || first_tf_.isZero() || msg->header.stamp <= first_tf_) return;
      // The bag opens with the static transforms (latched, as rosbag record
      // keeps them) and a camera_info, before any image.
      auto latched = boost::make_shared<ros::M_string>();
      (*latched)["latching"] = "1";
      (*latched)["callerid"] = "/camera_mount";
      (*latched)["type"] = ros::message_traits::datatype<tf2_msgs::TFMessage>();
      (*latched)["md5sum"] = ros::message_traits::md5sum<tf2_msgs::TFMessage>();
      (*latched)["message_definition"] = ros::message_traits::definition<tf2_msgs::TFMessage>();
      for (const tf2_msgs::TFMessage& m : statics_) bag_.write("/tf_static", first_tf_, m, latched);
      bag_.write("/depth/camera_info", first_tf_, *info_);
      armed_ = true;
    }
    bag_.write("/depth/image", msg->header.stamp, *msg);
    relay_.publish(msg);
    ++images_;
  }
  void onInfo(const sensor_msgs::CameraInfoConstPtr& msg) {
    std::lock_guard<std::mutex> l(mutex_);
    info_ = msg;
    if (armed_ && !closed_ && !images_stopped_) bag_.write("/depth/camera_info", msg->header.stamp, *msg);
  }
  void onTf(const tf2_msgs::TFMessageConstPtr& msg) {
    std::lock_guard<std::mutex> l(mutex_);
    ros::Time newest;
    for (const auto& t : msg->transforms) newest = std::max(newest, t.header.stamp);
    if (closed_ || newest.isZero()) return;
    if (first_tf_.isZero() || newest < first_tf_) first_tf_ = newest;
    bag_.write("/tf", newest, *msg);
  }
  void onTfStatic(const tf2_msgs::TFMessageConstPtr& msg) {
    std::lock_guard<std::mutex> l(mutex_);
    statics_.push_back(*msg);
  }
  void onClock(const rosgraph_msgs::ClockConstPtr& msg) {
    std::lock_guard<std::mutex> l(mutex_);
    if (!closed_ && !msg->clock.isZero()) bag_.write("/clock", msg->clock, *msg);
  }

  mutable std::mutex mutex_;
  rosbag::Bag bag_;
  ros::Publisher relay_;
  std::vector<ros::Subscriber> subs_;
  sensor_msgs::CameraInfoConstPtr info_;
  std::vector<tf2_msgs::TFMessage> statics_;
  ros::Time first_tf_;
  bool armed_ = false, images_stopped_ = false, closed_ = false;
  size_t images_ = 0;
};

// A TCP port nobody listens on now, for the replay's own master.
int freePort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof(addr);
  int port = -1;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0) {
    port = ntohs(addr.sin_port);
  }
  ::close(fd);
  return port;
}

// Starts argv (searched on PATH) in a process group of its own, with
// ROS_MASTER_URI set to `master` and its output appended to `log`; returns
// its pid, or -1. posix_spawn, not fork: this process has threads.
pid_t spawn(const std::vector<std::string>& argv, const std::string& master, const std::string& log) {
  std::vector<std::string> env_strings{"ROS_MASTER_URI=" + master};
  for (char** e = environ; *e != nullptr; ++e) {
    if (std::strncmp(*e, "ROS_MASTER_URI=", 15) != 0) env_strings.emplace_back(*e);
  }
  std::vector<char*> args, env;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  for (const std::string& e : env_strings) env.push_back(const_cast<char*>(e.c_str()));
  args.push_back(nullptr);
  env.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attr, 0);
  pid_t pid = -1;
  if (posix_spawnp(&pid, args[0], &actions, &attr, args.data(), env.data()) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  return pid;
}

// SIGINT to the process group (roslaunch stops its nodes and its master),
// SIGKILL if it is still there after `grace` seconds.
void stopGroup(pid_t pid, double grace) {
  ::kill(-pid, SIGINT);
  for (double waited = 0.0; waited < grace; waited += 0.2) {
    if (::waitpid(pid, nullptr, WNOHANG) == pid) return;
    ros::WallDuration(0.2).sleep();
  }
  ::kill(-pid, SIGKILL);
  ::waitpid(pid, nullptr, 0);
}

// True when the master on `port` knows `node`.
bool nodeExists(int port, const std::string& node) {
  XmlRpc::XmlRpcClient client("127.0.0.1", port, "/");
  XmlRpc::XmlRpcValue args, result;
  args[0] = "/test_mission_replay";
  args[1] = node;
  const bool ok = client.execute("lookupNode", args, result) && result.getType() == XmlRpc::XmlRpcValue::TypeArray &&
                  static_cast<int>(result[0]) == 1;
  client.close();
  return ok;
}

struct ReplaySettings {
  std::string bag, config, dir;
  double rate = 4.0;
  double timeout = 300.0;  // wall seconds for one replay
};

// Plays the bag through map_bag.launch on a fresh master, saves the map as
// dir/name through tsdf_mapper/save_map and loads it into *map.
Status replayBag(const ReplaySettings& s, const std::string& name, TsdfMap* map) {
  const int port = freePort();
  if (port < 0) return Status::Error("no free port for the replay's master");
  const std::string master = "http://127.0.0.1:" + std::to_string(port);
  const std::string log = s.dir + "/" + name + ".log";
  std::filesystem::remove(s.dir + "/" + name);
  std::filesystem::remove(log);
  char rate[32];
  std::snprintf(rate, sizeof(rate), "%g", s.rate);
  const pid_t launch = spawn({"roslaunch", "-p", std::to_string(port), "surface_nbv", "map_bag.launch", "bag:=" + s.bag,
                              "config:=" + s.config, "rate:=" + std::string(rate), "map_directory:=" + s.dir},
                             master, log);
  if (launch < 0) return Status::Error(name + ": cannot start roslaunch");
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(s.timeout);
  // The player shows up within a minute (master, nodes, bag index) or it died.
  const ros::WallTime start_deadline = ros::WallTime::now() + ros::WallDuration(60.0);
  bool started = false, finished = false;
  while (!finished && ros::WallTime::now() < deadline && (started || ros::WallTime::now() < start_deadline)) {
    ros::WallDuration(1.0).sleep();
    const bool playing = nodeExists(port, "/player");
    started = started || playing;
    finished = started && !playing && nodeExists(port, "/tsdf_mapper");
  }
  Status status = Status::Ok();
  if (!finished) {
    const std::string what = started ? "did not end within " + std::to_string(s.timeout) + " s" : "never started";
    status = Status::Error(name + ": the player " + what + ", see " + log);
  } else {
    // Frames may still wait for their transform (tf_wait): let them land.
    ros::WallDuration(2.0).sleep();
    // catkin's cached test environment may carry an empty PYTHONPATH (it is
    // written before the devel space holds Python messages): name it here.
    const std::string save = "PYTHONPATH=" NBV_DEVEL_PYTHONPATH ":${PYTHONPATH:-} ROS_MASTER_URI=" + master +
                             " rosservice call /tsdf_mapper/save_map \"path: '" + name + "'\" >> " + log + " 2>&1";
    if (std::system(save.c_str()) != 0) status = Status::Error(name + ": rosservice call failed, see " + log);
  }
  stopGroup(launch, 30.0);
  if (!status) return status;
  return loadMap(s.dir + "/" + name, map);
}

// Known voxels (W >= W_th) of two maps and how many are known in both with
// the same sign of phi.
struct Agreement {
  size_t known_a = 0, known_b = 0, both = 0, same_sign = 0;
};

size_t countKnown(const TsdfMap& map) {
  size_t known = 0;
  for (const auto& block : map.blocks()) {
    for (const TsdfVoxel& v : block->voxels) known += map.stateOf(v) != VoxelState::kUnknown ? 1 : 0;
  }
  return known;
}

Agreement compareMaps(const TsdfMap& a, const TsdfMap& b) {
  Agreement r;
  r.known_a = countKnown(a);
  r.known_b = countKnown(b);
  for (const auto& block : a.blocks()) {
    const TsdfBlock* other = b.block(block->index);
    if (other == nullptr) continue;
    for (int i = 0; i < kBlockVoxels; ++i) {
      const TsdfVoxel &va = block->voxels[i], &vb = other->voxels[i];
      if (a.stateOf(va) == VoxelState::kUnknown || b.stateOf(vb) == VoxelState::kUnknown) continue;
      ++r.both;
      r.same_sign += (va.phi <= 0.0f) == (vb.phi <= 0.0f) ? 1 : 0;
    }
  }
  return r;
}

// Phase 1: waits until the mission is DONE (or `timeout` wall seconds).
PlannerStatus waitForMission(ros::NodeHandle& nh, double timeout) {
  std::mutex mutex;
  PlannerStatus status;
  ros::Subscriber sub = nh.subscribe<PlannerStatus>("planner/status", 10, [&](const PlannerStatusConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex);
    status = *m;
  });
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::WallTime::now() < deadline) {
    ros::WallDuration(0.5).sleep();
    std::lock_guard<std::mutex> l(mutex);
    if (status.state == "DONE") break;
  }
  std::lock_guard<std::mutex> l(mutex);
  return status;
}

}  // namespace

TEST(MissionReplay, RecordedMissionReplaysToTheLiveMapAndRepeats) {
  ros::NodeHandle nh, priv("~");
  ReplaySettings replay;
  double mission_timeout = 420.0;
  ASSERT_TRUE(priv.getParam("out_dir", replay.dir));
  ASSERT_TRUE(priv.getParam("config", replay.config));
  priv.getParam("replay_rate", replay.rate);
  priv.getParam("replay_timeout", replay.timeout);
  priv.getParam("mission_timeout", mission_timeout);
  std::filesystem::create_directories(replay.dir);
  replay.bag = replay.dir + "/mission.bag";
  TsdfConfig map_config;
  const Status shared = loadSharedMapConfig("/nbv", &map_config);
  ASSERT_TRUE(shared.ok()) << shared.message();

  std::atomic<uint64_t> live_frames{0};
  ros::Subscriber stats = nh.subscribe<NodeStats>("tsdf/stats", 10, [&](const NodeStatsConstPtr& m) {
    for (const Counter& c : m->counters) {
      if (c.name == "frames_integrated") live_frames = c.count;
    }
  });
  ros::AsyncSpinner spinner(1);
  spinner.start();
  StreamRecorder recorder(nh, replay.bag);
  // The planner waits (start_running false) until the live mapper is fed
  // from the recorder, else it may plan on a map that has seen nothing.
  for (int i = 0; i < 600 && recorder.images() < 10; ++i) ros::WallDuration(0.2).sleep();
  ASSERT_GE(recorder.images(), 10u) << "no depth images to record";
  ros::ServiceClient start = nh.serviceClient<std_srvs::Trigger>("nbv_planner/start");
  ASSERT_TRUE(start.waitForExistence(ros::Duration(30.0)));
  std_srvs::Trigger trigger;
  ASSERT_TRUE(start.call(trigger) && trigger.response.success) << trigger.response.message;
  const PlannerStatus status = waitForMission(nh, mission_timeout);
  recorder.stopImages();
  EXPECT_EQ(status.state, "DONE") << status.reason << ": " << status.message;
  std::printf("mission: %s (%s), %.1f s of flight, %.1f m, %zu images recorded\n", status.state.c_str(),
              status.reason.c_str(), status.flight_time, status.path_length, recorder.images());
  ASSERT_GT(recorder.images(), 50u);
  // Relayed frames still in flight or waiting for their transform land first.
  ros::WallDuration(3.0).sleep();
  ros::ServiceClient save = nh.serviceClient<FilePath>("tsdf_mapper/save_map");
  ASSERT_TRUE(save.waitForExistence(ros::Duration(10.0)));
  FilePath srv;
  srv.request.path = "live.tsdf";
  ASSERT_TRUE(save.call(srv));
  ASSERT_EQ(srv.response.code, 0) << srv.response.message;
  recorder.close();
  ros::WallDuration(1.5).sleep();  // one more tsdf/stats
  std::printf("bag: %.1f MB, %zu images; the live mapper integrated %llu\n", std::filesystem::file_size(replay.bag) / 1e6,
              recorder.images(), static_cast<unsigned long long>(live_frames.load()));

  TsdfMap live(map_config), first(map_config), second(map_config);
  const Status live_loaded = loadMap(replay.dir + "/live.tsdf", &live);
  ASSERT_TRUE(live_loaded.ok()) << live_loaded.message();
  const Status s1 = replayBag(replay, "replay_1.tsdf", &first);
  ASSERT_TRUE(s1.ok()) << s1.message();
  const Status s2 = replayBag(replay, "replay_2.tsdf", &second);
  ASSERT_TRUE(s2.ok()) << s2.message();

  const Agreement a = compareMaps(live, first);
  const double difference = 100.0 * std::abs(static_cast<double>(a.known_b) - a.known_a) / a.known_a;
  const double sign = a.both > 0 ? 100.0 * a.same_sign / a.both : 0.0;
  std::printf("known voxels: live %zu, replay %zu (%.3f %% apart); known in both %zu, same sign %.3f %%\n", a.known_a,
              a.known_b, difference, a.both, sign);
  const uint64_t h1 = fuzz::mapDigest(first), h2 = fuzz::mapDigest(second);
  std::printf("replays: %zu and %zu known voxels; map hashes %016llx, %016llx (%s)\n", countKnown(first),
              countKnown(second), static_cast<unsigned long long>(h1),
              static_cast<unsigned long long>(h2), h1 == h2 ? "equal" : "DIFFERENT");
  ASSERT_GT(a.known_a, 10000u);
  EXPECT_LE(difference, 1.0);
  EXPECT_GE(sign, 99.0);
  EXPECT_EQ(h1, h2) << "the same bag replayed twice gave two maps";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_mission_replay");
  return RUN_ALL_TESTS();
}
