// libFuzzer target: depth images, point clouds and camera infos (layout in
// depth_input.h) through fromImageMsg, fromPointCloud2Msg and
// fromCameraInfoMsg. Aborts when the accept decision disagrees with the
// contract (test/fuzz/contracts.h), when an accepted output is inconsistent
// with its message, or when a refusal touched the output.
#include <cmath>
#include <cstdint>

#include "../test/fuzz/contracts.h"
#include "depth_input.h"
#include "fuzz_support.h"
#include "surface_nbv/ros/depth_conversions.h"

using namespace surface_nbv;
using namespace surface_nbv::fuzz;

namespace {

void fuzzImage(ByteReader& in) {
  const sensor_msgs::Image msg = decodeImage(in);
  DepthImage depth;
  depth.resize(2, 1);
  depth.data[0] = 42.0f;
  const Status s = fromImageMsg(msg, &depth);
  FUZZ_CHECK(s.ok() == imageContractHolds(msg), s.message());
  if (!s) {
    FUZZ_CHECK(depth.width == 2 && depth.height == 1 && depth.data.size() == 2 && depth.data[0] == 42.0f,
               "a refused image changed the output");
    return;
  }
  FUZZ_CHECK(depth.width == static_cast<int>(msg.width) && depth.height == static_cast<int>(msg.height) &&
                 depth.data.size() == static_cast<size_t>(msg.width) * msg.height,
             "output size");
  for (uint32_t r = 0; r < msg.height; ++r) {
    for (uint32_t c = 0; c < msg.width; ++c) {
      const float z = depth.at(static_cast<int>(r), static_cast<int>(c));
      const float want = referenceDepth(msg, r, c);
      FUZZ_CHECK(sameBits(z, want) || (std::isnan(z) && std::isnan(want)), "pixel value");
      FUZZ_CHECK(std::isnan(z) || std::isinf(z) || z > 0.0f, "a finite depth <= 0 passed");
    }
  }
}

void fuzzCloud(ByteReader& in) {
  const sensor_msgs::PointCloud2 msg = decodeCloud(in);
  std::vector<Eigen::Vector3f> points(1, Eigen::Vector3f(7, 7, 7));
  const Status s = fromPointCloud2Msg(msg, &points);
  uint64_t offsets[3] = {0, 0, 0};
  FUZZ_CHECK(s.ok() == cloudContractHolds(msg, offsets), s.message());
  if (!s) {
    FUZZ_CHECK(points.size() == 1 && points[0] == Eigen::Vector3f(7, 7, 7), "a refused cloud changed the output");
    return;
  }
  FUZZ_CHECK(points.size() == static_cast<size_t>(msg.width) * msg.height, "output size");
  for (uint32_t r = 0; msg.width > 0 && r < msg.height; ++r) {
    for (uint32_t c = 0; c < msg.width; ++c) {
      const size_t base = static_cast<size_t>(r) * msg.row_step + static_cast<size_t>(c) * msg.point_step;
      for (int k = 0; k < 3; ++k) {
        FUZZ_CHECK(base + offsets[k] + 4 <= msg.data.size(), "a point lies beyond the data");
        float want;
        std::memcpy(&want, msg.data.data() + base + offsets[k], 4);
        FUZZ_CHECK(sameBits(points[static_cast<size_t>(r) * msg.width + c][k], want), "point value");
      }
    }
  }
}

void fuzzCameraInfo(ByteReader& in) {
  const sensor_msgs::CameraInfo msg = decodeCameraInfo(in);
  CameraConfig base;
  const DepthCamera sentinel(base);
  DepthCamera camera = sentinel;
  const Status s = fromCameraInfoMsg(msg, base, &camera);
  if (!s) {
    FUZZ_CHECK(camera.fx() == sentinel.fx() && camera.cx() == sentinel.cx() && camera.width() == sentinel.width(),
               "a refused camera_info changed the output");
    return;
  }
  FUZZ_CHECK(camera.width() == static_cast<int>(msg.width) && camera.height() == static_cast<int>(msg.height),
             "camera size");
  FUZZ_CHECK(camera.fx() > 0 && camera.fy() > 0 && std::isfinite(camera.fx()) && std::isfinite(camera.fy()),
             "focal lengths");
  FUZZ_CHECK(camera.config().validate().ok(), camera.config().validate().message());
  for (double col : {-0.5, camera.width() - 0.5}) {
    for (double row : {-0.5, camera.height() - 0.5}) {
      FUZZ_CHECK(camera.pixelRay(col, row).allFinite(), "a corner ray is not finite");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  ByteReader in(data + 1, size - 1);
  switch (static_cast<DepthInputKind>(data[0] % 3)) {
    case DepthInputKind::kImage: fuzzImage(in); break;
    case DepthInputKind::kCloud: fuzzCloud(in); break;
    case DepthInputKind::kCameraInfo: fuzzCameraInfo(in); break;
  }
  return 0;
}
