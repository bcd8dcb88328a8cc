// One section of a YAML config ("nbv", "mission", ...) as a ParamSource
// (util/param_source.h): the reading side of nbv_mission and the tools, as
// ros/param_reader.h is the nodes'. yaml-cpp; ROS-free.
#pragma once

#include <set>
#include <string>

#include <yaml-cpp/yaml.h>

#include "surface_nbv/util/param_source.h"

namespace surface_nbv {

class YamlParamSource : public ParamSource {
 public:
  // `name` prefixes errors and given keys ("nbv"); `given` (optional)
  // collects "name/key" of every key present that was asked for.
  YamlParamSource(const YAML::Node& node, std::string name, std::set<std::string>* given = nullptr);

  using ParamSource::get;
  void get(const std::string& key, double* value) override;
  void get(const std::string& key, int* value) override;
  void get(const std::string& key, bool* value) override;
  void get(const std::string& key, std::string* value) override;
  void get(const std::string& key, uint64_t* value) override;
  void get(const std::string& key, std::vector<double>* value) override;
  bool has(const std::string& key) override;
  void fail(const std::string& key, const std::string& why) override;
  Status status() const override { return status_; }

  // Whether the section is there (a map).
  bool present() const { return node_ && node_.IsMap(); }
  // Every key of the section must have been asked for (its first key only,
  // for a nested one): else an error naming it.
  void refuseUnknown() override;

 private:
  // The node at `key` (nested by '/'), or an undefined node.
  YAML::Node find(const std::string& key);
  template <typename T>
  void read(const std::string& key, T* value, const char* expected);

  YAML::Node node_;
  std::string name_;
  std::set<std::string>* given_ = nullptr;
  std::set<std::string> seen_;
  Status status_;
};

}  // namespace surface_nbv
