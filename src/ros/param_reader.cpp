#include "surface_nbv/ros/param_reader.h"

#include <cmath>

namespace surface_nbv {
namespace {

bool toDouble(XmlRpc::XmlRpcValue& v, double* out) {
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) *out = static_cast<double>(v);
  else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) *out = static_cast<int>(v);
  else return false;
  return true;
}

}  // namespace

bool ParamReader::fetch(const std::string& key, XmlRpc::XmlRpcValue* v) {
  used_.insert(nh_.resolveName(key));
  return nh_.getParam(key, *v);
}

void ParamReader::fail(const std::string& key, const std::string& what) {
  errors_.push_back(nh_.resolveName(key) + " " + what);
}

void ParamReader::get(const std::string& key, double* value) {
  XmlRpc::XmlRpcValue v;
  if (!fetch(key, &v)) return;
  double d;
  if (!toDouble(v, &d)) return fail(key, "expected a number");
  *value = d;
}

void ParamReader::get(const std::string& key, int* value) {
  XmlRpc::XmlRpcValue v;
  if (!fetch(key, &v)) return;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) return fail(key, "expected an integer");
  *value = static_cast<int>(v);
}

void ParamReader::get(const std::string& key, uint64_t* value) {
  XmlRpc::XmlRpcValue v;
  if (!fetch(key, &v)) return;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeInt || static_cast<int>(v) < 0) {
    return fail(key, "expected a non-negative integer");
  }
  *value = static_cast<uint64_t>(static_cast<int>(v));
}

void ParamReader::get(const std::string& key, bool* value) {
  XmlRpc::XmlRpcValue v;
  if (!fetch(key, &v)) return;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeBoolean) return fail(key, "expected true or false");
  *value = static_cast<bool>(v);
}

void ParamReader::get(const std::string& key, std::string* value) {
  XmlRpc::XmlRpcValue v;
  if (!fetch(key, &v)) return;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeString) return fail(key, "expected a string");
  *value = static_cast<std::string>(v);
}

void ParamReader::get(const std::string& key, std::vector<double>* value) {
  XmlRpc::XmlRpcValue v;
  if (!fetch(key, &v)) return;
  if (v.getType() != XmlRpc::XmlRpcValue::TypeArray) return fail(key, "expected a list of numbers");
  std::vector<double> out;
  for (int i = 0; i < v.size(); ++i) {
    double d;
    if (!toDouble(v[i], &d)) return fail(key, "expected a list of numbers");
    out.push_back(d);
  }
  *value = out;
}

bool ParamReader::has(const std::string& key) {
  used_.insert(nh_.resolveName(key));
  return nh_.hasParam(key);
}

void ParamReader::checkUnknown(const std::string& prefix) {
  std::vector<std::string> names;
  if (!nh_.getParamNames(names)) return;
  std::string root = nh_.resolveName(prefix);
  if (root.empty() || root.back() != '/') root += '/';
  for (const std::string& name : names) {
    if (name.compare(0, root.size(), root) != 0) continue;
    bool known = used_.count(name) > 0;
    for (const std::string& u : used_) known = known || name.compare(0, u.size() + 1, u + "/") == 0;
    if (!known) errors_.push_back(name + " is not a parameter of this node (misspelt?)");
  }
}

Status ParamReader::status() const {
  if (errors_.empty()) return Status::Ok();
  std::string msg = errors_.front();
  if (errors_.size() > 1) msg += " (and " + std::to_string(errors_.size() - 1) + " more)";
  return Status::Error(msg);
}

}  // namespace surface_nbv
