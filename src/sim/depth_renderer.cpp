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

}  // namespace

float noisyDepth(float z, double k, uint64_t seed, uint64_t frame, uint64_t pixel) {
  return static_cast<float>(z + k * static_cast<double>(z) * z * sensorGaussian(seed, frame, pixel, 0));
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

void DepthRenderer::frameRays(const Transform& T_W_C, FrameRays* rays) const {
  const Eigen::Matrix3d R = T_W_C.linear();
  rays->origin = T_W_C.translation().cast<float>();
  rays->r02 = R(0, 2);
  rays->r12 = R(1, 2);
  const int width = camera_.width(), height = camera_.height();
  const int cols = (width + kRowsPerTask - 1) / kRowsPerTask * kRowsPerTask;
  const int rows = (height + kRowsPerTask - 1) / kRowsPerTask * kRowsPerTask;
  rays->col_x.resize(cols), rays->col_y.resize(cols), rays->col_z.resize(cols);
  rays->row_x.resize(rows), rays->row_y.resize(rows), rays->row_z.resize(rows);
  for (int col = 0; col < cols; ++col) {
    const double x = ray_x_[std::min(col, width - 1)];
    rays->col_x[col] = R(0, 0) * x;
    rays->col_y[col] = R(1, 0) * x;
    rays->col_z[col] = R(2, 0) * x;
  }
  for (int row = 0; row < rows; ++row) {
    const double y = ray_y_[std::min(row, height - 1)];
    rays->row_x[row] = R(0, 1) * y;
    rays->row_y[row] = R(1, 1) * y;
    rays->row_z[row] = R(2, 1) * y + R(2, 2);
  }
}

void DepthRenderer::render(const Transform& T_W_C, DepthImage* image, uint64_t frame_index) const {
  const CameraConfig& cfg = camera_.config();
  const bool measured = cfg.noise_k > 0.0 || cfg.sensor.enabled();
  if (!measured) {
    traceRows(T_W_C, image, nullptr, false);
    return;
  }
  // A real sensor: trace the true depth (and, for grazing dropouts, each
  // hit's incidence), then measure it (sensor_model.h).
  DepthImage raw;
  std::vector<float> cos_incidence;
  if (cfg.sensor.grazing_dropout_deg > 0.0) {
    cos_incidence.assign(static_cast<size_t>(camera_.width()) * camera_.height(), 1.0f);
  }
  traceRows(T_W_C, &raw, cos_incidence.empty() ? nullptr : &cos_incidence, true);
  applySensorModel(camera_, T_W_C, frame_index, raw, cos_incidence, image, threads_);
}

void DepthRenderer::traceRows(const Transform& T_W_C, DepthImage* image, std::vector<float>* cos_incidence,
                              bool raw) const {
  image->resize(camera_.width(), camera_.height());
  const int height = camera_.height();
  FrameRays rays;
  frameRays(T_W_C, &rays);
  TileOutput out{image, cos_incidence ? cos_incidence->data() : nullptr, raw};
  if (threads_ == 1) {
    renderRows(rays, 0, height, out);
    return;
  }
  const size_t bands = static_cast<size_t>((height + kRowsPerTask - 1) / kRowsPerTask);
  parallelFor(bands, threads_, [&](size_t band) {
    const int row = static_cast<int>(band) * kRowsPerTask;
    renderRows(rays, row, std::min(height, row + kRowsPerTask), out);
  });
}

void DepthRenderer::renderRows(const FrameRays& rays, int row_begin, int row_end, const TileOutput& out) const {
  if (packet_width_ == 16) {
    renderTiles<RTCRayHit16, 4, 4>(rays, row_begin, row_end, out);
  } else if (packet_width_ == 8) {
    renderTiles<RTCRayHit8, 4, 2>(rays, row_begin, row_end, out);
  } else {
    renderTiles<RTCRayHit4, 2, 2>(rays, row_begin, row_end, out);
  }
}

// The ray of pixel (col, row) is R (x_col, y_row, 1), its z at unit depth, so
// a hit's t is the depth. Rows 0 and 1 of R * Vector3d(x, y, 1) are summed
// as (R0 x + R1 y) + R2 and row 2 as R0 x + (R1 y + R2), as Eigen sums them,
// so these images are those of the product (test
// DepthRenderer.RaysAreTheRotatedPixelRays).
template <typename Packet, int TileW, int TileH>
void DepthRenderer::renderTiles(const FrameRays& rays, int row_begin, int row_end, const TileOutput& tile_out) const {
  DepthImage* image = tile_out.image;
  static_assert(kRowsPerTask % TileW == 0 && kRowsPerTask % TileH == 0, "frame rays are padded to whole tiles");
  const CameraConfig& cfg = camera_.config();
  const float min_z = static_cast<float>(cfg.min_range);
  const float max_z = static_cast<float>(cfg.max_range);
  const int width = camera_.width();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) Packet packet;
  alignas(64) int valid[TileW * TileH];

  for (int k = 0; k < TileW * TileH; ++k) {
    packet.ray.org_x[k] = rays.origin.x();
    packet.ray.org_y[k] = rays.origin.y();
    packet.ray.org_z[k] = rays.origin.z();
    packet.ray.id[k] = static_cast<unsigned>(k);
    packet.ray.tnear[k] = 0.0f;
    packet.ray.time[k] = 0.0f;
    packet.ray.mask[k] = 0xFFFFFFFFu;
    packet.ray.flags[k] = 0;
  }
  // Embree writes only tfar and the hit of a packet's rays.
  for (int row0 = row_begin; row0 < row_end; row0 += TileH) {
    for (int col0 = 0; col0 < width; col0 += TileW) {
      for (int tr = 0; tr < TileH; ++tr) {
        const int row = row0 + tr;
        const double rx = rays.row_x[row], ry = rays.row_y[row], rz = rays.row_z[row];
        for (int tc = 0; tc < TileW; ++tc) {
          const int k = tr * TileW + tc, col = col0 + tc;
          valid[k] = row < row_end && col < width ? -1 : 0;
          packet.ray.dir_x[k] = static_cast<float>((rays.col_x[col] + rx) + rays.r02);
          packet.ray.dir_y[k] = static_cast<float>((rays.col_y[col] + ry) + rays.r12);
          packet.ray.dir_z[k] = static_cast<float>(rays.col_z[col] + rz);
          packet.ray.tfar[k] = max_z;
          packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        }
      }
      intersect(valid, scene_.handle(), &context, &packet);
      // REP 117: +Inf = no return within max range, -Inf = too close. Selects,
      // not branches: hits and misses mix unpredictably along a tile.
      for (int tr = 0; tr < TileH && row0 + tr < row_end; ++tr) {
        float* out = &image->at(row0 + tr, col0);
        for (int tc = 0; tc < TileW && col0 + tc < width; ++tc) {
          const int k = tr * TileW + tc;
          float z = packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID ? packet.ray.tfar[k] : kInf;
          if (tile_out.raw) {  // the true depth, for the sensor model
            out[tc] = z;
            if (tile_out.cos_incidence && z != kInf) {
              const Eigen::Vector3f n(packet.hit.Ng_x[k], packet.hit.Ng_y[k], packet.hit.Ng_z[k]);
              const Eigen::Vector3f d(packet.ray.dir_x[k], packet.ray.dir_y[k], packet.ray.dir_z[k]);
              const float nd = n.norm() * d.norm();
              tile_out.cos_incidence[static_cast<size_t>(row0 + tr) * width + col0 + tc] =
                  nd > 0.0f ? std::abs(n.dot(d)) / nd : 1.0f;
            }
            continue;
          }
          z = z < min_z ? -kInf : z;
          out[tc] = z <= max_z ? z : kInf;  // NaN too
        }
      }
    }
  }
}

}  // namespace surface_nbv
