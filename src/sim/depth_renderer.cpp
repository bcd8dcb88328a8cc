#include "surface_nbv/sim/depth_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {
namespace {

constexpr int kRowsPerTask = 4;  // a multiple of every tile's height

void intersect(int* valid, RTCScene scene, RTCIntersectContext* context, RTCRayHit4* packet) {
  rtcIntersect4(valid, scene, context, packet);
}
void intersect(int* valid, RTCScene scene, RTCIntersectContext* context, RTCRayHit8* packet) {
  rtcIntersect8(valid, scene, context, packet);
}
void intersect(int* valid, RTCScene scene, RTCIntersectContext* context, RTCRayHit16* packet) {
  rtcIntersect16(valid, scene, context, packet);
}

uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

double toUnit(uint64_t x) { return (static_cast<double>(x >> 11) + 0.5) * (1.0 / 9007199254740992.0); }

}  // namespace

float noisyDepth(float z, double k, uint64_t seed, uint64_t frame, uint64_t pixel) {
  const uint64_t key = splitmix64(splitmix64(seed) ^ splitmix64(frame + 0x632BE59BD9B4E019ull) ^ pixel);
  const double u1 = toUnit(splitmix64(key));
  const double u2 = toUnit(splitmix64(key ^ 0xD1B54A32D192ED03ull));
  const double gauss = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  return static_cast<float>(z + k * static_cast<double>(z) * z * gauss);
}

DepthRenderer::DepthRenderer(const RaycastScene& scene, const DepthCamera& camera, int threads, int packet_width)
    : scene_(scene),
      camera_(camera),
      threads_(std::max(1, threads)),
      packet_width_(packet_width == 4 || packet_width == 8 || packet_width == 16 ? packet_width
                                                                                 : scene.nativePacketWidth()) {
  for (int col = 0; col < camera_.width(); ++col) ray_x_.push_back(camera_.pixelRay(col, 0).x());
  for (int row = 0; row < camera_.height(); ++row) ray_y_.push_back(camera_.pixelRay(0, row).y());
}

void DepthRenderer::render(const Transform& T_W_C, DepthImage* image, uint64_t frame_index) const {
  image->resize(camera_.width(), camera_.height());
  const int height = camera_.height();
  if (threads_ == 1) {
    renderRows(T_W_C, 0, height, frame_index, image);
    return;
  }
  const size_t bands = static_cast<size_t>((height + kRowsPerTask - 1) / kRowsPerTask);
  parallelFor(bands, threads_, [&](size_t band) {
    const int row = static_cast<int>(band) * kRowsPerTask;
    renderRows(T_W_C, row, std::min(height, row + kRowsPerTask), frame_index, image);
  });
}

void DepthRenderer::renderRows(const Transform& T_W_C, int row_begin, int row_end, uint64_t frame_index,
                               DepthImage* image) const {
  if (packet_width_ == 16) {
    renderTiles<RTCRayHit16, 4, 4>(T_W_C, row_begin, row_end, frame_index, image);
  } else if (packet_width_ == 8) {
    renderTiles<RTCRayHit8, 4, 2>(T_W_C, row_begin, row_end, frame_index, image);
  } else {
    renderTiles<RTCRayHit4, 2, 2>(T_W_C, row_begin, row_end, frame_index, image);
  }
}

template <typename Packet, int TileW, int TileH>
void DepthRenderer::renderTiles(const Transform& T_W_C, int row_begin, int row_end, uint64_t frame_index,
                                DepthImage* image) const {
  const CameraConfig& cfg = camera_.config();
  const Eigen::Matrix3d R = T_W_C.linear();
  const Eigen::Vector3d o = T_W_C.translation();
  const float min_z = static_cast<float>(cfg.min_range);
  const float max_z = static_cast<float>(cfg.max_range);
  const int width = camera_.width();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) Packet packet;
  alignas(64) int valid[TileW * TileH];

  for (int k = 0; k < TileW * TileH; ++k) {
    packet.ray.org_x[k] = static_cast<float>(o.x());
    packet.ray.org_y[k] = static_cast<float>(o.y());
    packet.ray.org_z[k] = static_cast<float>(o.z());
    packet.ray.id[k] = static_cast<unsigned>(k);
  }
  for (int row0 = row_begin; row0 < row_end; row0 += TileH) {
    for (int col0 = 0; col0 < width; col0 += TileW) {
      for (int k = 0; k < TileW * TileH; ++k) {
        const int row = row0 + k / TileW, col = col0 + k % TileW;
        valid[k] = row < row_end && col < width ? -1 : 0;
        const Eigen::Vector3d d =
            R * Eigen::Vector3d(ray_x_[std::min(col, width - 1)], ray_y_[std::min(row, row_end - 1)], 1.0);
        packet.ray.dir_x[k] = static_cast<float>(d.x());
        packet.ray.dir_y[k] = static_cast<float>(d.y());
        packet.ray.dir_z[k] = static_cast<float>(d.z());
        packet.ray.tnear[k] = 0.0f;
        packet.ray.tfar[k] = max_z;
        packet.ray.time[k] = 0.0f;
        packet.ray.mask[k] = 0xFFFFFFFFu;
        packet.ray.flags[k] = 0;
        packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
      }
      intersect(valid, scene_.handle(), &context, &packet);
      for (int k = 0; k < TileW * TileH; ++k) {
        if (!valid[k]) continue;
        const int row = row0 + k / TileW, col = col0 + k % TileW;
        // REP 117: +Inf = no return within max range, -Inf = too close.
        float z = std::numeric_limits<float>::infinity();
        if (packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) {
          z = packet.ray.tfar[k];
          if (cfg.noise_k > 0.0) {
            z = noisyDepth(z, cfg.noise_k, cfg.noise_seed, frame_index, static_cast<uint64_t>(row) * width + col);
          }
          if (z < min_z) z = -std::numeric_limits<float>::infinity();
          else if (!(z <= max_z)) z = std::numeric_limits<float>::infinity();
        }
        image->at(row, col) = z;
      }
    }
  }
}

}  // namespace surface_nbv
