// Where a config struct's keys come from: one section of a YAML file
// (config/yaml_param_source.h, nbv_mission and the tools) or one ROS
// namespace (ros/param_reader.h, the nodes). The readers of config_keys.h
// take a ParamSource, so every key is read by one function and checked by
// its struct's validate() only: a file nbv_mission refuses, the nodes refuse.
//
// Keys may name a nested key with '/' ("camera/width"). An absent key leaves
// the value as it is; a present key of the wrong type is an error naming
// the source and the key, and the first error is kept (status()).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/util/status.h"

namespace surface_nbv {

class ParamSource {
 public:
  virtual ~ParamSource() = default;

  virtual void get(const std::string& key, double* value) = 0;
  virtual void get(const std::string& key, int* value) = 0;
  virtual void get(const std::string& key, bool* value) = 0;
  virtual void get(const std::string& key, std::string* value) = 0;
  virtual void get(const std::string& key, uint64_t* value) = 0;  // also size_t
  virtual void get(const std::string& key, std::vector<double>* value) = 0;
  // Whether the key is there (of any type); counts as asked for.
  virtual bool has(const std::string& key) = 0;
  // Records "<source>/<key> <why>" as an error (the first one is kept).
  virtual void fail(const std::string& key, const std::string& why) = 0;
  virtual Status status() const = 0;
  // Records the first key there that no get() or has() asked for as an error.
  virtual void refuseUnknown() = 0;

  // Built on the above.
  void get(const std::string& key, float* value);
  void get(const std::string& key, unsigned int* value);
  void get(const std::string& key, Eigen::Vector3d* value);  // [x, y, z]
  void get(const std::string& key, Eigen::Vector4d* value);  // [x, y, z, yaw]
};

}  // namespace surface_nbv
