// Test-side driver of a real tsdf_mapper node for the timestamp / TF and the
// service rostests (mapper_time.test, mapper_services.test). It publishes
// /clock (the launch files set use_sim_time), /tf, depth/camera_info and
// depth/image itself, reads the node's counters from tsdf/stats and takes a
// digest of the map through ~save_map. Frames are 64 x 48 depth images of a
// plane 2 m ahead; the camera looks along world +z from a pose chosen by the
// caller. Thread safety: the counters and the last tsdf/update are guarded by
// a mutex; every other method is meant for the test thread. MapperTestNode is
// the start both tests' main functions share.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <tuple>

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2_msgs/TFMessage.h>

#include "surface_nbv/FilePath.h"
#include "surface_nbv/NodeStats.h"
#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/map_io.h"
#include "surface_nbv/ros/depth_conversions.h"
#include "surface_nbv/ros/mapper_params.h"

namespace surface_nbv {

using Counters = std::map<std::string, uint64_t>;

// What a saved map holds: blocks, voxels known at w_th and a 64-bit FNV-1a
// hash of every block index and voxel, in block index order.
struct MapDigest {
  bool valid = false;
  size_t blocks = 0;
  size_t known = 0;
  uint64_t hash = 0;
  std::string error;
};

inline bool operator==(const MapDigest& a, const MapDigest& b) {
  return a.valid && b.valid && a.blocks == b.blocks && a.known == b.known && a.hash == b.hash;
}
inline bool operator!=(const MapDigest& a, const MapDigest& b) { return !(a == b); }
inline std::ostream& operator<<(std::ostream& os, const MapDigest& d) {
  if (!d.valid) return os << "(no map: " << d.error << ")";
  return os << "(" << d.blocks << " blocks, " << d.known << " known, hash " << std::hex << d.hash << std::dec << ")";
}

inline MapDigest digestOf(const TsdfMap& map) {
  MapDigest d;
  d.valid = true;
  d.blocks = map.numBlocks();
  std::map<std::tuple<int, int, int>, const TsdfBlock*> sorted;
  for (const auto& b : map.blocks()) sorted[{b->index.x(), b->index.y(), b->index.z()}] = b.get();
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  for (const auto& [index, block] : sorted) {
    mix(block->index.data(), 3 * sizeof(int));
    mix(block->voxels.data(), sizeof(block->voxels));
    for (const TsdfVoxel& v : block->voxels) d.known += v.w >= map.config().w_th ? 1 : 0;
  }
  d.hash = h;
  return d;
}

class MapperProbe {
 public:
  // `dir` is the mapper's map_directory; `mapper` its node name.
  MapperProbe(const std::string& dir, const std::string& mapper) : dir_(dir), mapper_(mapper) {}
  ~MapperProbe() {
    running_ = false;
    if (clock_thread_.joinable()) clock_thread_.join();
  }

  // Advertises, subscribes and waits until the mapper listens; false if it never does.
  bool start() {
    clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
    tf_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf", 100);
    image_pub_ = nh_.advertise<sensor_msgs::Image>("depth/image", 100);
    info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>("depth/camera_info", 1, true);
    stats_sub_ = nh_.subscribe<NodeStats>("tsdf/stats", 10, [this](const NodeStatsConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      for (const Counter& c : m->counters) counters_[c.name] = c.count;
      ++stats_received_;
    });
    update_sub_ = nh_.subscribe<TsdfUpdate>("tsdf/update", 10, [this](const TsdfUpdateConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      last_update_ = *m;
      ++updates_received_;
      snapshots_received_ += m->snapshot ? 1 : 0;
    });
    running_ = true;
    clock_thread_ = std::thread([this] {
      while (running_ && ros::ok()) {
        rosgraph_msgs::Clock c;
        c.clock = ros::Time(now_.load());
        clock_pub_.publish(c);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    });
    if (!loadSharedMapConfig("/nbv", &map_config_)) return false;
    CameraConfig cc;
    cc.width = 64;
    cc.height = 48;
    cc.min_range = 0.5;
    camera_ = std::make_unique<DepthCamera>(cc);
    sensor_msgs::CameraInfo info;
    std_msgs::Header h;
    h.frame_id = "cam";
    h.stamp = ros::Time(now_.load());
    toCameraInfoMsg(*camera_, h, &info);
    info_pub_.publish(info);
    const bool connected = waitUntil(
        [this] {
          return image_pub_.getNumSubscribers() > 0 && tf_pub_.getNumSubscribers() > 0 &&
                 info_pub_.getNumSubscribers() > 0 && clock_pub_.getNumSubscribers() > 0;
        },
        30.0);
    if (!connected) return false;
    ros::WallDuration(0.5).sleep();  // the mapper's own connections settle
    return ros::service::waitForService(mapper_ + "/save_map", ros::Duration(30.0)) && freshStats(2);
  }

  // Sim time: published on /clock every 20 ms.
  void setClock(double t) { now_ = t; }
  double clock() const { return now_.load(); }

  geometry_msgs::TransformStamped transform(const std::string& child, double stamp, const Eigen::Vector3d& p,
                                            const std::string& parent = "world") const {
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time(stamp);
    t.header.frame_id = parent;
    t.child_frame_id = child;
    t.transform.translation.x = p.x();
    t.transform.translation.y = p.y();
    t.transform.translation.z = p.z();
    t.transform.rotation.w = 1.0;
    return t;
  }
  void publishTf(const geometry_msgs::TransformStamped& t) {
    tf2_msgs::TFMessage m;
    m.transforms.push_back(t);
    tf_pub_.publish(m);
  }
  void publishTf(const std::string& child, double stamp, const Eigen::Vector3d& p) {
    publishTf(transform(child, stamp, p));
  }
  // A depth image of a plane `depth` metres ahead; a zero `stamp` is sent as zero.
  void publishFrame(const std::string& frame_id, double stamp, float depth = 2.0f) {
    DepthImage image;
    image.resize(camera_->width(), camera_->height());
    for (float& d : image.data) d = depth;
    std_msgs::Header h;
    h.frame_id = frame_id;
    h.stamp = stamp == 0.0 ? ros::Time() : ros::Time(stamp);
    sensor_msgs::Image msg;
    toImageMsg(image, h, &msg);
    image_pub_.publish(msg);
  }

  Counters counters() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counters_;
  }
  // Waits for `n` tsdf/stats messages published after this call.
  bool freshStats(int n, double seconds = 10.0) {
    const uint64_t start = statsReceived();
    return waitUntil([&] { return statsReceived() >= start + n; }, seconds);
  }
  uint64_t statsReceived() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return stats_received_;
  }
  uint64_t updatesReceived() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return updates_received_;
  }
  uint64_t snapshotsReceived() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return snapshots_received_;
  }
  TsdfUpdate lastUpdate() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_update_;
  }

  // Calls one of the mapper's FilePath services; false if the call itself failed.
  bool callFile(const std::string& service, const std::string& name, int* code, std::string* message) {
    FilePath srv;
    srv.request.path = name;
    if (!ros::service::call(mapper_ + "/" + service, srv)) return false;
    *code = srv.response.code;
    *message = srv.response.message;
    return true;
  }
  // The digest of the mapper's map as saved under `name` by ~save_map.
  MapDigest digest(const std::string& name = "digest.map") {
    MapDigest d;
    int code = -1;
    std::string message;
    if (!callFile("save_map", name, &code, &message) || code != 0) {
      d.error = "save_map " + name + ": code " + std::to_string(code) + " " + message;
      return d;
    }
    return digestOfFile(dir_ + "/" + name);
  }
  MapDigest digestOfFile(const std::string& path) const {
    MapDigest d;
    TsdfMap map(map_config_);
    if (Status s = loadMap(path, &map); !s) {
      d.error = s.message();
      return d;
    }
    return digestOf(map);
  }
  const TsdfConfig& mapConfig() const { return map_config_; }
  const std::string& dir() const { return dir_; }

  static bool waitUntil(const std::function<bool()>& predicate, double seconds) {
    const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::WallTime::now() < end) {
      if (predicate()) return true;
      ros::WallDuration(0.02).sleep();
    }
    return predicate();
  }

 private:
  ros::NodeHandle nh_;
  std::string dir_, mapper_;
  TsdfConfig map_config_;
  std::unique_ptr<DepthCamera> camera_;
  ros::Publisher clock_pub_, tf_pub_, image_pub_, info_pub_;
  ros::Subscriber stats_sub_, update_sub_;
  std::atomic<double> now_{1000.0};
  std::atomic<bool> running_{false};
  std::thread clock_thread_;
  mutable std::mutex mutex_;
  Counters counters_;
  uint64_t stats_received_ = 0;
  uint64_t updates_received_ = 0;
  uint64_t snapshots_received_ = 0;
  TsdfUpdate last_update_;
};

// What the mains of the mapper rostests share, built after ros::init: a
// running two-thread spinner and a started probe. `ok` is false, and the
// reason printed, when the mapper did not come up.
struct MapperTestNode {
  MapperTestNode(const std::string& dir, const std::string& mapper) : spinner(2), probe(dir, mapper) {
    spinner.start();
    ok = probe.start();
    if (!ok) std::fprintf(stderr, "%s did not come up\n", mapper.c_str());
  }
  ros::AsyncSpinner spinner;
  MapperProbe probe;
  bool ok = false;
};

inline uint64_t delta(const Counters& before, const Counters& after, const std::string& name) {
  const auto b = before.find(name), a = after.find(name);
  return (a == after.end() ? 0 : a->second) - (b == before.end() ? 0 : b->second);
}

}  // namespace surface_nbv
