// Typed reading of ROS parameters into core config structs. Absent keys keep
// the struct's default; a key of the wrong type, or (with checkUnknown) a key
// nobody reads, is an error naming the key, so a misspelt parameter stops the
// node instead of being silently ignored.
#pragma once

#include <set>
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <Eigen/Core>

#include "surface_nbv/util/status.h"

namespace surface_nbv {

// Where the configs' `tracker:` section (the simulated UAV's limits) lives by
// default; mpc_tracker and nbv_planner read it (~tracker_namespace).
inline constexpr char kTrackerNamespace[] = "/tracker";
// Where the configs' `nbv:` section (map, camera, planning parameters every
// node shares) lives by default (~shared_namespace).
inline constexpr char kSharedNamespace[] = "/nbv";

class ParamReader {
 public:
  explicit ParamReader(const ros::NodeHandle& nh) : nh_(nh) {}

  void get(const std::string& key, double* value);
  void get(const std::string& key, int* value);
  void get(const std::string& key, bool* value);
  void get(const std::string& key, std::string* value);
  void get(const std::string& key, Eigen::Vector3d* value);
  void get(const std::string& key, std::vector<double>* value);
  void get(const std::string& key, uint64_t* value);

  // Records every parameter under `prefix` (relative to the handle's
  // namespace, "" for all of it) that no get() asked for as an error.
  void checkUnknown(const std::string& prefix = "");
  // The first error met, or Ok.
  Status status() const;
  const std::string& ns() const { return nh_.getNamespace(); }

 private:
  bool fetch(const std::string& key, XmlRpc::XmlRpcValue* v);
  void fail(const std::string& key, const std::string& what);

  ros::NodeHandle nh_;
  std::set<std::string> used_;
  std::vector<std::string> errors_;
};

}  // namespace surface_nbv
