// Independent readings of the message contracts of depth_conversions.h, used
// as oracles by the fuzz tests and the libFuzzer targets: whether a message
// must be accepted, and what an accepted one holds.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

namespace surface_nbv {
namespace fuzz {

inline bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

// The depth at (r, c) of an image that the contract accepts, decoded here
// independently of fromImageMsg (REP 118 / REP 117: +-Inf are kept, NaN,
// zero and negative depths become NaN).
inline float referenceDepth(const sensor_msgs::Image& msg, uint32_t r, uint32_t c) {
  const bool is_float = msg.encoding == "32FC1";
  const size_t pixel = is_float ? 4 : 2;
  const size_t at = static_cast<size_t>(r) * msg.step + c * pixel;
  uint32_t raw = 0;
  for (size_t k = 0; k < pixel; ++k) {
    const size_t shift = msg.is_bigendian ? 8 * (pixel - 1 - k) : 8 * k;
    raw |= static_cast<uint32_t>(msg.data.at(at + k)) << shift;
  }
  float z;
  if (is_float) {
    std::memcpy(&z, &raw, 4);
  } else {
    z = 0.001f * static_cast<uint16_t>(raw);
  }
  return std::isinf(z) || (std::isfinite(z) && z > 0.0f) ? z : std::numeric_limits<float>::quiet_NaN();
}

inline bool imageContractHolds(const sensor_msgs::Image& msg) {
  const bool is_float = msg.encoding == "32FC1";
  const bool is_mm = msg.encoding == "16UC1" || msg.encoding == "mono16";
  if (!is_float && !is_mm) return false;
  if (msg.width < 1 || msg.height < 1 || msg.width > 16384 || msg.height > 16384) return false;
  const uint64_t pixel = is_float ? 4 : 2;
  return msg.step >= msg.width * pixel && msg.data.size() >= uint64_t{msg.step} * msg.height;
}

// The float32 x, y, z layout of the cloud contract: each name present, every
// field of that name a single float32 (the last one is read), inside
// point_step, x, y and z not overlapping, little-endian, rows and data long
// enough.
inline bool cloudContractHolds(const sensor_msgs::PointCloud2& msg, uint64_t offsets[3]) {
  const char* names[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    bool found = false;
    for (const sensor_msgs::PointField& f : msg.fields) {
      if (f.name != names[i]) continue;
      if (f.datatype != sensor_msgs::PointField::FLOAT32 || f.count != 1) return false;
      offsets[i] = f.offset;
      found = true;
    }
    if (!found || offsets[i] + 4 > msg.point_step) return false;
  }
  for (int i = 0; i < 3; ++i) {
    const uint64_t a = offsets[i], b = offsets[(i + 1) % 3];
    if (a < b + 4 && b < a + 4) return false;  // x, y and z must not overlap
  }
  if (msg.is_bigendian) return false;
  if (uint64_t{msg.width} * msg.height > 50000000ull) return false;
  return uint64_t{msg.row_step} >= uint64_t{msg.width} * msg.point_step &&
         msg.data.size() >= uint64_t{msg.row_step} * msg.height;
}

}  // namespace fuzz
}  // namespace surface_nbv
