#include "surface_nbv/util/param_source.h"

#include <limits>

namespace surface_nbv {

void ParamSource::get(const std::string& key, float* value) {
  double d = *value;
  get(key, &d);
  *value = static_cast<float>(d);
}

void ParamSource::get(const std::string& key, unsigned int* value) {
  uint64_t u = *value;
  get(key, &u);
  if (u > std::numeric_limits<unsigned int>::max()) return fail(key, "expected an integer below 2^32");
  *value = static_cast<unsigned int>(u);
}

void ParamSource::get(const std::string& key, Eigen::Vector3d* value) {
  if (!has(key)) return;
  std::vector<double> v;
  get(key, &v);
  if (!status()) return;
  if (v.size() != 3) return fail(key, "expected [x, y, z]");
  *value = Eigen::Vector3d(v[0], v[1], v[2]);
}

void ParamSource::get(const std::string& key, Eigen::Vector4d* value) {
  if (!has(key)) return;
  std::vector<double> v;
  get(key, &v);
  if (!status()) return;
  if (v.size() != 4) return fail(key, "expected [x, y, z, yaw]");
  *value = Eigen::Vector4d(v[0], v[1], v[2], v[3]);
}

}  // namespace surface_nbv
