#include "message_cases.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <sensor_msgs/image_encodings.h>

namespace surface_nbv {
namespace fuzz {
namespace {

const char* const kEncodings[] = {"32FC1", "16UC1", "mono16", "8UC1",   "mono8",  "rgb8",   "32FC3",
                                  "16SC1", "64FC1", "",       "32fc1",  "32FC1 ", "bgr16",  "32FC"};

template <typename T>
void putBytes(std::vector<uint8_t>* data, size_t at, T value, bool big_endian) {
  uint8_t b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  std::memcpy(data->data() + at, b, sizeof(T));
}

// Sets a ros::Time or ros::Duration field by field, as a deserialiser does:
// the constructors normalise and may throw, the wire does neither.
template <typename T>
void rawTime(Mutator& m, T* t) {
  switch (m.below(5)) {
    case 0: t->sec = std::numeric_limits<decltype(t->sec)>::max(); break;
    case 1: t->sec = std::numeric_limits<decltype(t->sec)>::min(); break;
    case 2: t->nsec = static_cast<decltype(t->nsec)>(m.bits32()); break;
    case 3: t->sec = static_cast<decltype(t->sec)>(m.bits32()); break;
    default: t->sec = 0; t->nsec = 0; break;
  }
}

}  // namespace

TsdfConfig fuzzMapConfig() {
  TsdfConfig config;
  config.voxel_size = 0.25;
  config.w_th = 0.3f;
  config.bounds = AlignedBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(8, 8, 4));
  config.max_blocks = 24;
  return config;
}

void scribbleMap(TsdfMap* map, int blocks, Mutator& m) {
  const Eigen::Vector3i grid = map->gridBlocks();
  for (int b = 0; b < blocks; ++b) {
    const Eigen::Vector3i index(m.below(grid.x()), m.below(grid.y()), m.below(grid.z()));
    TsdfBlock* block = map->allocateBlock(index);
    if (block == nullptr) continue;  // at the block cap
    for (TsdfVoxel& v : block->voxels) {
      v.phi = static_cast<float>(m.uniform(-0.75, 0.75));
      v.w = m.chance(0.2) ? 0.0f : static_cast<float>(m.uniform(0.0, 5.0));
    }
    block->change_stamp = map->beginChange();
  }
}

sensor_msgs::Image seedImage(Mutator& m) {
  sensor_msgs::Image msg;
  const int kind = m.below(3);
  msg.encoding = kind == 0 ? "32FC1" : kind == 1 ? "16UC1" : "mono16";
  const size_t pixel = kind == 0 ? 4 : 2;
  msg.width = 1 + m.below(24);
  msg.height = 1 + m.below(16);
  msg.is_bigendian = m.chance(0.2) ? 1 : 0;
  msg.step = static_cast<uint32_t>(msg.width * pixel + (m.chance(0.3) ? m.below(9) : 0));
  msg.data.assign(static_cast<size_t>(msg.step) * msg.height, 0);
  for (uint32_t r = 0; r < msg.height; ++r) {
    for (uint32_t c = 0; c < msg.width; ++c) {
      const size_t at = static_cast<size_t>(r) * msg.step + c * pixel;
      const bool hole = m.chance(0.1);
      if (kind == 0) {
        putBytes(&msg.data, at, hole ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(m.uniform(0.2, 9.0)),
                 msg.is_bigendian);
      } else {
        putBytes(&msg.data, at, static_cast<uint16_t>(hole ? 0 : 200 + m.below(9000)), msg.is_bigendian);
      }
    }
  }
  return msg;
}

void mutateImage(Mutator& m, sensor_msgs::Image* msg) {
  const int edits = 1 + m.below(3);
  for (int e = 0; e < edits; ++e) {
    switch (m.below(8)) {
      case 0: msg->encoding = kEncodings[m.below(sizeof(kEncodings) / sizeof(kEncodings[0]))]; break;
      case 1: msg->width = m.hostileSize(msg->width); break;
      case 2: msg->height = m.hostileSize(msg->height); break;
      case 3: msg->step = m.hostileSize(msg->step); break;
      case 4: msg->is_bigendian = static_cast<uint8_t>(m.bits32()); break;
      case 5: m.mutateBytes(&msg->data); break;
      case 6: msg->data.resize(m.below(static_cast<int>(msg->data.size()) + 1)); break;
      default:
        // Hostile depth values in place: NaN, Inf, zero, negative, huge.
        for (int k = 0; k < 8 && msg->data.size() >= 4; ++k) {
          const float z = m.hostileFloat();
          std::memcpy(msg->data.data() + m.below(static_cast<int>(msg->data.size()) - 3), &z, 4);
        }
        break;
    }
  }
}

sensor_msgs::CameraInfo seedCameraInfo(Mutator& m) {
  sensor_msgs::CameraInfo msg;
  msg.width = 8 + m.below(633);
  msg.height = 8 + m.below(473);
  const double fx = m.uniform(0.3, 2.0) * msg.width, fy = m.uniform(0.3, 2.0) * msg.height;
  const double cx = 0.5 * (msg.width - 1) + m.uniform(-3, 3), cy = 0.5 * (msg.height - 1) + m.uniform(-3, 3);
  msg.distortion_model = "plumb_bob";
  msg.D.assign(5, 0.0);
  msg.K = {fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0};
  msg.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  msg.P = {fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return msg;
}

void mutateCameraInfo(Mutator& m, sensor_msgs::CameraInfo* msg) {
  const int edits = 1 + m.below(3);
  for (int e = 0; e < edits; ++e) {
    switch (m.below(7)) {
      case 0: msg->K[m.below(9)] = m.hostileDouble(); break;
      case 1: msg->K[m.chance(0.5) ? 0 : 4] = m.hostileDouble(); break;
      case 2: msg->K[m.chance(0.5) ? 2 : 5] = m.hostileDouble(); break;
      case 3: msg->width = m.hostileSize(msg->width); break;
      case 4: msg->height = m.hostileSize(msg->height); break;
      case 5: msg->P[m.below(12)] = m.hostileDouble(); break;
      default:
        msg->D.resize(m.below(20), m.hostileDouble());
        msg->distortion_model = m.chance(0.5) ? "" : "rational_polynomial";
        break;
    }
  }
}

sensor_msgs::PointCloud2 seedCloud(Mutator& m) {
  sensor_msgs::PointCloud2 msg;
  msg.height = m.chance(0.3) ? 1 + m.below(6) : 1;
  msg.width = 1 + m.below(40);
  // x, y, z in a random order after an optional leading field, then extras.
  std::vector<std::string> names = {"x", "y", "z"};
  std::shuffle(names.begin(), names.end(), m.rng());
  uint32_t offset = m.chance(0.3) ? 4 : 0;
  if (offset > 0) {
    sensor_msgs::PointField f;
    f.name = "intensity";
    f.offset = 0;
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    msg.fields.push_back(f);
  }
  for (const std::string& name : names) {
    sensor_msgs::PointField f;
    f.name = name;
    f.offset = offset;
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    msg.fields.push_back(f);
    offset += 4;
  }
  if (m.chance(0.3)) {
    sensor_msgs::PointField f;
    f.name = "rgb";
    f.offset = offset;
    f.datatype = sensor_msgs::PointField::UINT32;
    f.count = 1;
    msg.fields.push_back(f);
    offset += 4;
  }
  msg.point_step = offset + (m.chance(0.3) ? 4 * m.below(3) : 0);
  msg.row_step = msg.point_step * msg.width + (m.chance(0.2) ? m.below(16) : 0);
  msg.is_bigendian = false;
  msg.is_dense = false;
  msg.data.resize(static_cast<size_t>(msg.row_step) * msg.height);
  for (size_t i = 0; i + 4 <= msg.data.size(); i += 4) {
    const float v = m.chance(0.05) ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(m.uniform(-9, 9));
    std::memcpy(msg.data.data() + i, &v, 4);
  }
  return msg;
}

void mutateCloud(Mutator& m, sensor_msgs::PointCloud2* msg) {
  const int edits = 1 + m.below(3);
  for (int e = 0; e < edits; ++e) {
    const int nf = static_cast<int>(msg->fields.size());
    switch (m.below(11)) {
      case 0:
        if (nf > 0) msg->fields.erase(msg->fields.begin() + m.below(nf));  // a missing field
        break;
      case 1:
        if (nf > 0) msg->fields.push_back(msg->fields[m.below(nf)]);  // a repeated field
        break;
      case 2:
        if (nf > 0) msg->fields[m.below(nf)].offset = m.chance(0.5) ? m.below(24) : m.hostileSize(12);  // overlap
        break;
      case 3:
        if (nf > 0) msg->fields[m.below(nf)].datatype = static_cast<uint8_t>(m.below(10));
        break;
      case 4:
        if (nf > 0) msg->fields[m.below(nf)].count = m.below(4);
        break;
      case 5:
        if (nf > 0) msg->fields[m.below(nf)].name = m.chance(0.5) ? "X" : "x ";
        break;
      case 6: msg->point_step = m.hostileSize(msg->point_step); break;
      case 7: msg->row_step = m.hostileSize(msg->row_step); break;
      case 8:
        if (m.chance(0.5)) msg->width = m.hostileSize(msg->width);
        else msg->height = m.hostileSize(msg->height);
        break;
      case 9:
        if (m.chance(0.5)) msg->data.resize(m.below(static_cast<int>(msg->data.size()) + 1));  // truncated
        else m.mutateBytes(&msg->data);
        break;
      default: msg->is_bigendian = !msg->is_bigendian; break;
    }
  }
}

void mutateUpdate(Mutator& m, surface_nbv::TsdfUpdate* msg) {
  const int edits = 1 + m.below(3);
  for (int e = 0; e < edits; ++e) {
    const int nb = static_cast<int>(msg->blocks.size());
    surface_nbv::TsdfVoxelBlock* block = nb > 0 ? &msg->blocks[m.below(nb)] : nullptr;
    switch (m.below(14)) {
      case 0: msg->sequence += static_cast<uint64_t>(m.below(5)) - 2; break;
      case 1: msg->sequence = m.chance(0.5) ? 0 : std::numeric_limits<uint64_t>::max(); break;
      case 2: msg->snapshot = !msg->snapshot; break;
      case 3:
        msg->voxel_size = m.chance(0.5) ? m.hostileDouble() : std::nextafter(msg->voxel_size, 1.0);
        break;
      case 4: msg->w_th = m.chance(0.5) ? m.hostileFloat() : std::nextafter(msg->w_th, 1.0f); break;
      case 5: {
        geometry_msgs::Point& p = m.chance(0.5) ? msg->bounds_min : msg->bounds_max;
        (m.chance(0.5) ? p.x : p.z) = m.hostileDouble();
        break;
      }
      case 6:
        if (nb > 0) msg->blocks.erase(msg->blocks.begin() + m.below(nb));
        break;
      case 7:
        if (nb > 0) msg->blocks.push_back(*block);  // a repeated block
        break;
      case 8:
        if (block) {
          int32_t& c = m.chance(0.33) ? block->x : m.chance(0.5) ? block->y : block->z;
          const int32_t choices[] = {-1, 4, 2, 1 << 30, std::numeric_limits<int32_t>::min(),
                                    static_cast<int32_t>(static_cast<uint32_t>(c) + 1u),
                                    static_cast<int32_t>(static_cast<uint32_t>(c) - 1u)};
          c = choices[m.below(7)];
        }
        break;
      case 9:
        if (block) (m.chance(0.5) ? block->phi : block->w).resize(m.chance(0.5) ? m.below(600) : 511);
        break;
      case 10:
        if (block && !block->phi.empty()) block->phi[m.below(static_cast<int>(block->phi.size()))] = m.hostileFloat();
        break;
      case 11:
        if (block && !block->w.empty()) block->w[m.below(static_cast<int>(block->w.size()))] = m.hostileFloat();
        break;
      case 12:
        // A harmless change of values: the update stays valid.
        if (block && !block->phi.empty()) {
          block->phi[m.below(static_cast<int>(block->phi.size()))] = static_cast<float>(m.uniform(-0.5, 0.5));
        }
        break;
      default:
        if (nb >= 2) std::swap(msg->blocks[m.below(nb)], msg->blocks[m.below(nb)]);
        break;
    }
  }
}

trajectory_msgs::MultiDOFJointTrajectory seedTrajectory(Mutator& m, const Eigen::Vector3d& start_W) {
  trajectory_msgs::MultiDOFJointTrajectory msg;
  msg.header.frame_id = "world";
  if (m.chance(0.5)) msg.header.stamp.fromSec(m.uniform(0.0, 5.0));
  msg.joint_names = {"base_link"};
  Eigen::Vector3d p = start_W + Eigen::Vector3d(m.uniform(-0.5, 0.5), m.uniform(-0.5, 0.5), m.uniform(-0.5, 0.5));
  double t = m.uniform(0.0, 0.5);
  const int n = 1 + m.below(12);
  const bool velocities = m.chance(0.5);
  for (int i = 0; i < n; ++i) {
    trajectory_msgs::MultiDOFJointTrajectoryPoint q;
    geometry_msgs::Transform tf;
    tf.translation.x = p.x();
    tf.translation.y = p.y();
    tf.translation.z = p.z();
    const double yaw = m.uniform(-M_PI, M_PI);
    tf.rotation.w = std::cos(0.5 * yaw);
    tf.rotation.z = std::sin(0.5 * yaw);
    q.transforms.push_back(tf);
    if (velocities) {
      geometry_msgs::Twist v;
      v.linear.x = m.uniform(-0.5, 0.5);
      q.velocities.push_back(v);
    }
    q.time_from_start.fromSec(t);
    msg.points.push_back(q);
    t += m.uniform(0.1, 1.0);
    p += Eigen::Vector3d(m.uniform(-0.5, 0.5), m.uniform(-0.5, 0.5), m.uniform(-0.2, 0.2));
  }
  return msg;
}

void mutateTrajectory(Mutator& m, trajectory_msgs::MultiDOFJointTrajectory* msg) {
  const int edits = 1 + m.below(3);
  for (int e = 0; e < edits; ++e) {
    const int np = static_cast<int>(msg->points.size());
    trajectory_msgs::MultiDOFJointTrajectoryPoint* q = np > 0 ? &msg->points[m.below(np)] : nullptr;
    geometry_msgs::Transform* tf = q && !q->transforms.empty() ? &q->transforms[0] : nullptr;
    switch (m.below(12)) {
      case 0: msg->points.clear(); break;
      case 1:
        if (q) q->transforms.resize(m.chance(0.5) ? 0 : 2);
        break;
      case 2:
        if (tf) (m.chance(0.5) ? tf->translation.x : tf->translation.z) = m.hostileDouble();
        break;
      case 3:
        if (tf) (m.chance(0.5) ? tf->rotation.w : tf->rotation.z) = m.hostileDouble();
        break;
      case 4:
        if (tf) tf->rotation = geometry_msgs::Quaternion();  // all zero: an unset quaternion
        break;
      case 5:
        if (tf) {
          const double s = m.uniform(0.1, 10.0);  // a quaternion that is not of unit norm
          tf->rotation.w *= s;
          tf->rotation.z *= s;
        }
        break;
      case 6:
        if (q) rawTime(m, &q->time_from_start);
        break;
      case 7:
        if (np >= 2) std::swap(msg->points[m.below(np)].time_from_start, msg->points[m.below(np)].time_from_start);
        break;
      case 8: rawTime(m, &msg->header.stamp); break;
      case 9:
        if (q) {
          q->velocities.resize(1 + m.below(2));
          q->velocities[0].linear.y = m.hostileDouble();
        }
        break;
      case 10:
        if (np > 0) msg->points.push_back(msg->points.back());  // a repeated time
        break;
      default:
        if (tf) tf->translation.y += m.chance(0.5) ? 3.0 : 1e7;  // far from the UAV
        break;
    }
  }
}

}  // namespace fuzz
}  // namespace surface_nbv
