// The byte layout that fuzz_depth_conversions reads its messages from, and
// the encoders that make_seeds uses to write valid seeds in it. Byte 0 picks
// the message (mod 3):
//   0 Image:       u8 encoding (index into kFuzzEncodings), u8 is_bigendian,
//                  u32 width, u32 height, u32 step, then the data
//   1 PointCloud2: u8 field count (mod 9), per field u8 name (index into
//                  kFuzzFieldNames), u32 offset, u8 datatype, u32 count; then
//                  u32 point_step, u32 row_step, u32 width, u32 height,
//                  u8 is_bigendian, then the data
//   2 CameraInfo:  u32 width, u32 height, 9 x f64 K
// All little-endian; missing bytes read as zero.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include "fuzz_support.h"

namespace surface_nbv {
namespace fuzz {

constexpr const char* kFuzzEncodings[] = {"32FC1", "16UC1", "mono16", "8UC1", "rgb8", "32FC3", "64FC1", ""};
constexpr int kNumFuzzEncodings = sizeof(kFuzzEncodings) / sizeof(kFuzzEncodings[0]);
constexpr const char* kFuzzFieldNames[] = {"x", "y", "z", "rgb", "intensity", "X"};
constexpr int kNumFuzzFieldNames = sizeof(kFuzzFieldNames) / sizeof(kFuzzFieldNames[0]);

enum class DepthInputKind { kImage = 0, kCloud = 1, kCameraInfo = 2 };

inline sensor_msgs::Image decodeImage(ByteReader& in) {
  sensor_msgs::Image msg;
  msg.encoding = kFuzzEncodings[in.take<uint8_t>() % kNumFuzzEncodings];
  msg.is_bigendian = in.take<uint8_t>();
  msg.width = in.take<uint32_t>();
  msg.height = in.take<uint32_t>();
  msg.step = in.take<uint32_t>();
  msg.data.assign(in.rest(), in.rest() + in.restSize());
  return msg;
}

inline sensor_msgs::PointCloud2 decodeCloud(ByteReader& in) {
  sensor_msgs::PointCloud2 msg;
  const int fields = in.take<uint8_t>() % 9;
  for (int i = 0; i < fields; ++i) {
    sensor_msgs::PointField f;
    f.name = kFuzzFieldNames[in.take<uint8_t>() % kNumFuzzFieldNames];
    f.offset = in.take<uint32_t>();
    f.datatype = in.take<uint8_t>();
    f.count = in.take<uint32_t>();
    msg.fields.push_back(f);
  }
  msg.point_step = in.take<uint32_t>();
  msg.row_step = in.take<uint32_t>();
  msg.width = in.take<uint32_t>();
  msg.height = in.take<uint32_t>();
  msg.is_bigendian = in.take<uint8_t>() != 0;
  msg.data.assign(in.rest(), in.rest() + in.restSize());
  return msg;
}

inline sensor_msgs::CameraInfo decodeCameraInfo(ByteReader& in) {
  sensor_msgs::CameraInfo msg;
  msg.width = in.take<uint32_t>();
  msg.height = in.take<uint32_t>();
  for (double& k : msg.K) k = in.take<double>();
  return msg;
}

class ByteWriter {
 public:
  template <typename T>
  void put(T v) {
    const size_t at = bytes.size();
    bytes.resize(at + sizeof(T));
    std::memcpy(bytes.data() + at, &v, sizeof(T));
  }
  std::vector<uint8_t> bytes;
};

inline int encodingIndex(const std::string& encoding) {
  for (int i = 0; i < kNumFuzzEncodings; ++i) {
    if (encoding == kFuzzEncodings[i]) return i;
  }
  return kNumFuzzEncodings - 1;
}

inline int fieldNameIndex(const std::string& name) {
  for (int i = 0; i < kNumFuzzFieldNames; ++i) {
    if (name == kFuzzFieldNames[i]) return i;
  }
  return kNumFuzzFieldNames - 1;
}

inline std::vector<uint8_t> encodeImage(const sensor_msgs::Image& msg) {
  ByteWriter out;
  out.put<uint8_t>(static_cast<uint8_t>(DepthInputKind::kImage));
  out.put<uint8_t>(static_cast<uint8_t>(encodingIndex(msg.encoding)));
  out.put<uint8_t>(msg.is_bigendian);
  out.put<uint32_t>(msg.width);
  out.put<uint32_t>(msg.height);
  out.put<uint32_t>(msg.step);
  out.bytes.insert(out.bytes.end(), msg.data.begin(), msg.data.end());
  return out.bytes;
}

inline std::vector<uint8_t> encodeCloud(const sensor_msgs::PointCloud2& msg) {
  ByteWriter out;
  out.put<uint8_t>(static_cast<uint8_t>(DepthInputKind::kCloud));
  out.put<uint8_t>(static_cast<uint8_t>(msg.fields.size() % 9));
  for (size_t i = 0; i < msg.fields.size() % 9; ++i) {
    const sensor_msgs::PointField& f = msg.fields[i];
    out.put<uint8_t>(static_cast<uint8_t>(fieldNameIndex(f.name)));
    out.put<uint32_t>(f.offset);
    out.put<uint8_t>(f.datatype);
    out.put<uint32_t>(f.count);
  }
  out.put<uint32_t>(msg.point_step);
  out.put<uint32_t>(msg.row_step);
  out.put<uint32_t>(msg.width);
  out.put<uint32_t>(msg.height);
  out.put<uint8_t>(msg.is_bigendian ? 1 : 0);
  out.bytes.insert(out.bytes.end(), msg.data.begin(), msg.data.end());
  return out.bytes;
}

inline std::vector<uint8_t> encodeCameraInfo(const sensor_msgs::CameraInfo& msg) {
  ByteWriter out;
  out.put<uint8_t>(static_cast<uint8_t>(DepthInputKind::kCameraInfo));
  out.put<uint32_t>(msg.width);
  out.put<uint32_t>(msg.height);
  for (double k : msg.K) out.put<double>(k);
  return out.bytes;
}

}  // namespace fuzz
}  // namespace surface_nbv
