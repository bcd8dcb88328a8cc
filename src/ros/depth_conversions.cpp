#include "surface_nbv/ros/depth_conversions.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <sensor_msgs/image_encodings.h>

namespace surface_nbv {

void toImageMsg(const DepthImage& depth, const std_msgs::Header& header, sensor_msgs::Image* msg) {
  msg->header = header;
  msg->width = static_cast<uint32_t>(depth.width);
  msg->height = static_cast<uint32_t>(depth.height);
  msg->encoding = sensor_msgs::image_encodings::TYPE_32FC1;
  msg->is_bigendian = 0;
  msg->step = msg->width * sizeof(float);
  msg->data.resize(depth.data.size() * sizeof(float));
  std::memcpy(msg->data.data(), depth.data.data(), msg->data.size());
}

void toImageMsgMillimetres(const DepthImage& depth, const std_msgs::Header& header, sensor_msgs::Image* msg) {
  msg->header = header;
  msg->width = static_cast<uint32_t>(depth.width);
  msg->height = static_cast<uint32_t>(depth.height);
  msg->encoding = sensor_msgs::image_encodings::TYPE_16UC1;
  msg->is_bigendian = 0;
  msg->step = msg->width * sizeof(uint16_t);
  msg->data.resize(depth.data.size() * sizeof(uint16_t));
  for (size_t i = 0; i < depth.data.size(); ++i) {
    const float z = depth.data[i];
    const double mm = std::isfinite(z) && z > 0.0f ? std::round(1000.0 * z) : 0.0;
    const uint16_t value = mm >= 1.0 && mm <= 65535.0 ? static_cast<uint16_t>(mm) : 0;
    std::memcpy(msg->data.data() + 2 * i, &value, 2);
  }
}

Status fromImageMsg(const sensor_msgs::Image& msg, DepthImage* depth) {
  const bool is_float = msg.encoding == sensor_msgs::image_encodings::TYPE_32FC1;
  const bool is_mm = msg.encoding == sensor_msgs::image_encodings::TYPE_16UC1 ||
                     msg.encoding == sensor_msgs::image_encodings::MONO16;
  if (!is_float && !is_mm) return Status::Error("encoding '" + msg.encoding + "' is not 32FC1 or 16UC1");
  if (msg.width == 0 || msg.height == 0 || msg.width > 16384 || msg.height > 16384) {
    return Status::Error("image size " + std::to_string(msg.width) + "x" + std::to_string(msg.height) +
                         " is out of range");
  }
  const size_t pixel = is_float ? 4 : 2;
  if (msg.step < msg.width * pixel) return Status::Error("step " + std::to_string(msg.step) + " is too small");
  if (msg.data.size() < static_cast<size_t>(msg.step) * msg.height) {
    return Status::Error("data holds " + std::to_string(msg.data.size()) + " bytes, expected " +
                         std::to_string(static_cast<size_t>(msg.step) * msg.height));
  }
  const bool swap = msg.is_bigendian != 0;
  depth->resize(static_cast<int>(msg.width), static_cast<int>(msg.height));
  for (uint32_t r = 0; r < msg.height; ++r) {
    const uint8_t* row = msg.data.data() + static_cast<size_t>(r) * msg.step;
    for (uint32_t c = 0; c < msg.width; ++c) {
      uint8_t b[4];
      std::memcpy(b, row + c * pixel, pixel);
      if (swap) std::reverse(b, b + pixel);
      float z;
      if (is_float) {
        std::memcpy(&z, b, 4);
      } else {
        uint16_t mm;
        std::memcpy(&mm, b, 2);
        z = 0.001f * mm;
      }
      // REP 117: +-Inf pass through (no return / too close); NaN, zero and
      // negative depths become NaN (invalid).
      depth->at(static_cast<int>(r), static_cast<int>(c)) =
          std::isinf(z) || (std::isfinite(z) && z > 0.0f) ? z : std::numeric_limits<float>::quiet_NaN();
    }
  }
  return Status::Ok();
}

void toCameraInfoMsg(const DepthCamera& camera, const std_msgs::Header& header, sensor_msgs::CameraInfo* msg) {
  msg->header = header;
  msg->width = static_cast<uint32_t>(camera.width());
  msg->height = static_cast<uint32_t>(camera.height());
  msg->distortion_model = "plumb_bob";
  msg->D.assign(5, 0.0);
  msg->K = {camera.fx(), 0.0, camera.cx(), 0.0, camera.fy(), camera.cy(), 0.0, 0.0, 1.0};
  msg->R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  msg->P = {camera.fx(), 0.0, camera.cx(), 0.0, 0.0, camera.fy(), camera.cy(), 0.0, 0.0, 0.0, 1.0, 0.0};
  msg->binning_x = msg->binning_y = 0;
}

Status fromCameraInfoMsg(const sensor_msgs::CameraInfo& msg, const CameraConfig& base, DepthCamera* camera) {
  const double fx = msg.K[0], fy = msg.K[4], cx = msg.K[2], cy = msg.K[5];
  const double w = msg.width, h = msg.height;
  const bool ok = std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) && std::isfinite(cy) && fx > 0 &&
                  fy > 0 && msg.width > 0 && msg.height > 0 && msg.width <= 16384 && msg.height <= 16384 &&
                  cx >= -w && cx <= 2.0 * w && cy >= -h && cy <= 2.0 * h;
  if (!ok) {
    return Status::Error("camera_info refused (size " + std::to_string(msg.width) + "x" + std::to_string(msg.height) +
                         ", K = [" + std::to_string(fx) + " " + std::to_string(fy) + " " + std::to_string(cx) + " " +
                         std::to_string(cy) + "])");
  }
  CameraConfig c = base;
  c.width = static_cast<int>(msg.width);
  c.height = static_cast<int>(msg.height);
  const DepthCamera result(c, fx, fy, cx, cy);
  if (Status s = result.config().validate(); !s) return Status::Error("camera_info refused: " + s.message());
  *camera = result;
  return Status::Ok();
}

void toPointCloud2Msg(const std::vector<Eigen::Vector3f>& points, const std_msgs::Header& header,
                      sensor_msgs::PointCloud2* msg) {
  msg->header = header;
  msg->height = 1;
  msg->width = static_cast<uint32_t>(points.size());
  msg->fields.resize(3);
  const char* names[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    msg->fields[i].name = names[i];
    msg->fields[i].offset = static_cast<uint32_t>(4 * i);
    msg->fields[i].datatype = sensor_msgs::PointField::FLOAT32;
    msg->fields[i].count = 1;
  }
  msg->is_bigendian = false;
  msg->point_step = 12;
  msg->row_step = msg->point_step * msg->width;
  msg->is_dense = true;
  msg->data.resize(static_cast<size_t>(msg->row_step));
  for (size_t i = 0; i < points.size(); ++i) std::memcpy(msg->data.data() + 12 * i, points[i].data(), 12);
}

Status fromPointCloud2Msg(const sensor_msgs::PointCloud2& msg, std::vector<Eigen::Vector3f>* points) {
  int64_t offsets[3] = {-1, -1, -1};
  const char* names[3] = {"x", "y", "z"};
  for (const sensor_msgs::PointField& f : msg.fields) {
    for (int i = 0; i < 3; ++i) {
      if (f.name != names[i]) continue;
      if (f.datatype != sensor_msgs::PointField::FLOAT32 || f.count != 1) {
        return Status::Error(std::string("field ") + names[i] + " is not a single float32");
      }
      offsets[i] = static_cast<int64_t>(f.offset);
    }
  }
  for (int i = 0; i < 3; ++i) {
    if (offsets[i] < 0) return Status::Error(std::string("cloud has no field ") + names[i]);
    if (static_cast<uint64_t>(offsets[i]) + 4 > msg.point_step) return Status::Error("field offset beyond point_step");
  }
  for (int i = 0; i < 3; ++i) {
    const int64_t other = offsets[(i + 1) % 3];
    if (offsets[i] < other + 4 && other < offsets[i] + 4) return Status::Error("fields x, y and z overlap");
  }
  if (msg.is_bigendian) return Status::Error("big-endian clouds are not supported");
  const uint64_t n = static_cast<uint64_t>(msg.width) * msg.height;
  if (n > 50000000ull) return Status::Error("cloud of " + std::to_string(n) + " points is out of range");
  if (static_cast<uint64_t>(msg.row_step) < static_cast<uint64_t>(msg.width) * msg.point_step ||
      msg.data.size() < static_cast<uint64_t>(msg.row_step) * msg.height) {
    return Status::Error("cloud data holds " + std::to_string(msg.data.size()) + " bytes, too few for " +
                         std::to_string(n) + " points");
  }
  points->clear();
  // Without this, a cloud of width 0 and height 4e9 spins through 4e9 empty rows.
  if (n == 0) return Status::Ok();
  points->reserve(n);
  for (uint32_t r = 0; r < msg.height; ++r) {
    for (uint32_t c = 0; c < msg.width; ++c) {
      const uint8_t* p = msg.data.data() + static_cast<size_t>(r) * msg.row_step + static_cast<size_t>(c) * msg.point_step;
      Eigen::Vector3f q;
      for (int i = 0; i < 3; ++i) std::memcpy(&q[i], p + offsets[i], 4);
      points->push_back(q);
    }
  }
  return Status::Ok();
}

void toMeshMarker(const TriangleMesh& mesh, const std_msgs::Header& header, const std::string& ns,
                  visualization_msgs::Marker* marker) {
  marker->header = header;
  marker->ns = ns;
  marker->id = 0;
  marker->type = visualization_msgs::Marker::TRIANGLE_LIST;
  marker->action = visualization_msgs::Marker::ADD;
  marker->pose.orientation.w = 1.0;
  marker->scale.x = marker->scale.y = marker->scale.z = 1.0;
  marker->color.r = marker->color.g = marker->color.b = 0.7f;
  marker->color.a = 1.0f;
  marker->points.clear();
  marker->points.reserve(3 * mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      geometry_msgs::Point p;
      p.x = mesh.vertices[t[k]].x();
      p.y = mesh.vertices[t[k]].y();
      p.z = mesh.vertices[t[k]].z();
      marker->points.push_back(p);
    }
  }
}

Status fromTransformMsg(const geometry_msgs::Transform& msg, Transform* T) {
  const Eigen::Vector3d t(msg.translation.x, msg.translation.y, msg.translation.z);
  const Eigen::Quaterniond q(msg.rotation.w, msg.rotation.x, msg.rotation.y, msg.rotation.z);
  if (!t.allFinite() || !q.coeffs().allFinite()) return Status::Error("transform has non-finite values");
  if (std::abs(q.norm() - 1.0) > 1e-3) {
    return Status::Error("transform quaternion norm " + std::to_string(q.norm()) + " is not 1");
  }
  *T = Transform::Identity();
  T->linear() = q.normalized().toRotationMatrix();
  T->translation() = t;
  return Status::Ok();
}

}  // namespace surface_nbv
