#include "surface_nbv/config/yaml_param_source.h"

namespace surface_nbv {

YamlParamSource::YamlParamSource(const YAML::Node& node, std::string name, std::set<std::string>* given)
    : node_(node), name_(std::move(name)), given_(given) {}

YAML::Node YamlParamSource::find(const std::string& key) {
  seen_.insert(key.substr(0, key.find('/')));
  if (!present()) return YAML::Node(YAML::NodeType::Undefined);
  // Clones of handles, not assignments: assigning a YAML::Node rebinds the
  // node it refers to in the document.
  std::vector<YAML::Node> path{node_};
  size_t begin = 0;
  while (true) {
    const size_t slash = key.find('/', begin);
    const std::string part = key.substr(begin, slash == std::string::npos ? std::string::npos : slash - begin);
    const YAML::Node& here = path.back();
    if (!here.IsMap() || !here[part]) return YAML::Node(YAML::NodeType::Undefined);
    path.push_back(here[part]);
    if (slash == std::string::npos) return path.back();
    begin = slash + 1;
  }
}

bool YamlParamSource::has(const std::string& key) { return static_cast<bool>(find(key)); }

template <typename T>
void YamlParamSource::read(const std::string& key, T* value, const char* expected) {
  const YAML::Node n = find(key);
  if (!n) return;
  if (given_) given_->insert(name_ + "/" + key);
  if (!status_) return;
  try {
    *value = n.as<T>();
  } catch (const YAML::Exception&) {
    fail(key, std::string("has the wrong type (expected ") + expected + ")");
  }
}

void YamlParamSource::get(const std::string& key, double* value) { read(key, value, "a number"); }
void YamlParamSource::get(const std::string& key, int* value) { read(key, value, "an integer"); }
void YamlParamSource::get(const std::string& key, bool* value) { read(key, value, "true or false"); }
void YamlParamSource::get(const std::string& key, std::string* value) { read(key, value, "a string"); }
void YamlParamSource::get(const std::string& key, std::vector<double>* value) {
  read(key, value, "a list of numbers");
}

void YamlParamSource::get(const std::string& key, uint64_t* value) {
  const YAML::Node n = find(key);
  if (n && n.IsScalar() && !n.Scalar().empty() && n.Scalar()[0] == '-') {
    if (given_) given_->insert(name_ + "/" + key);
    return fail(key, "has the wrong type (expected a non-negative integer)");
  }
  read(key, value, "a non-negative integer");
}

void YamlParamSource::fail(const std::string& key, const std::string& why) {
  if (status_) status_ = Status::Error(name_ + "/" + key + " " + why);
}

void YamlParamSource::refuseUnknown() {
  if (!status_ || !present()) return;
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>();
    if (!seen_.count(key)) return fail(key, "is not a known key");
  }
}

}  // namespace surface_nbv
