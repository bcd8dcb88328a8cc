// Typed reading of ROS parameters into core config structs: the ROS side of
// ParamSource (util/param_source.h), so the readers of config/config_keys.h
// read a namespace as they read a YAML section. Absent keys keep the
// struct's default; a key of the wrong type, or (with checkUnknown) a key
// nobody reads, is an error naming the key, so a misspelt parameter stops the
// node instead of being silently ignored.
#pragma once

#include <set>
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <Eigen/Core>

#include "surface_nbv/util/param_source.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

// Where the configs' `tracker:` section (the simulated UAV's limits) lives by
// default; mpc_tracker and nbv_planner read it (~tracker_namespace).
inline constexpr char kTrackerNamespace[] = "/tracker";
// Where the configs' `nbv:` section (map, camera, planning parameters every
// node shares) lives by default (~shared_namespace).
inline constexpr char kSharedNamespace[] = "/nbv";

class ParamReader : public ParamSource {
 public:
  explicit ParamReader(const ros::NodeHandle& nh) : nh_(nh) {}

  using ParamSource::get;
  void get(const std::string& key, double* value) override;
  void get(const std::string& key, int* value) override;
  void get(const std::string& key, bool* value) override;
  void get(const std::string& key, std::string* value) override;
  void get(const std::string& key, std::vector<double>* value) override;
  void get(const std::string& key, uint64_t* value) override;
  bool has(const std::string& key) override;
  void fail(const std::string& key, const std::string& what) override;

  // Records every parameter under `prefix` (relative to the handle's
  // namespace, "" for all of it) that no get() asked for as an error.
  void checkUnknown(const std::string& prefix = "");
  void refuseUnknown() override { checkUnknown(); }
  // The first error met, or Ok.
  Status status() const override;
  const std::string& ns() const { return nh_.getNamespace(); }

 private:
  bool fetch(const std::string& key, XmlRpc::XmlRpcValue* v);

  ros::NodeHandle nh_;
  std::set<std::string> used_;
  std::vector<std::string> errors_;
};

}  // namespace surface_nbv
