#include "surface_nbv/eval/surface_sampler.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "surface_nbv/eval/counter_random.h"
#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {
namespace {

constexpr size_t kChunk = 4096;
constexpr uint64_t kStreamSample = 0x5a3d;

std::vector<double> cumulatedAreas(const TriangleMesh& mesh) {
  std::vector<double> cumulated(mesh.triangles.size());
  double sum = 0.0;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Eigen::Vector3i& t = mesh.triangles[i];
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.vertices[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.vertices[t[2]].cast<double>();
    const double area = 0.5 * (b - a).cross(c - a).norm();
    sum += std::isfinite(area) ? area : 0.0;
    cumulated[i] = sum;
  }
  return cumulated;
}

// ceil(area / spacing^2), forgiving the last bits of rounding (96 m^2 at
// 0.1 m is 9600 points, not 9601).
size_t countFor(double area, double spacing) {
  const double wanted = area / (spacing * spacing);
  return area > 0.0 ? static_cast<size_t>(std::ceil(wanted * (1.0 - 1e-12))) : 0;
}

}  // namespace

SurfaceSampler::SurfaceSampler(double spacing, uint64_t seed, int threads)
    : spacing_(spacing), seed_(seed), threads_(threads) {}

size_t SurfaceSampler::pointCount(const TriangleMesh& mesh) const {
  const std::vector<double> cumulated = cumulatedAreas(mesh);
  return countFor(cumulated.empty() ? 0.0 : cumulated.back(), spacing_);
}

Status SurfaceSampler::sample(const TriangleMesh& mesh, size_t max_points, SurfaceCloud* cloud) const {
  if (!(spacing_ > 0.0)) return Status::Error("point_spacing expected > 0");
  const std::vector<double> cumulated = cumulatedAreas(mesh);
  const double area = cumulated.empty() ? 0.0 : cumulated.back();
  const double wanted = area / (spacing_ * spacing_);
  if (!(wanted <= static_cast<double>(max_points))) {
    return Status::Error("point_spacing " + std::to_string(spacing_) + " m gives " +
                         std::to_string(static_cast<long long>(wanted)) + " points on " + std::to_string(area) +
                         " m^2, above max_points " + std::to_string(max_points));
  }
  const size_t n = countFor(area, spacing_);
  SurfaceCloud out;
  out.points.resize(n);
  out.normals.resize(n);
  out.triangles.resize(n);
  // Point k lies at cumulated area (k + u) * area / n: one point per stratum.
  parallelFor((n + kChunk - 1) / kChunk, threads_, [&](size_t chunk) {
    const size_t end = std::min(n, (chunk + 1) * kChunk);
    for (size_t k = chunk * kChunk; k < end; ++k) {
      const double at = (static_cast<double>(k) + counterUniform(seed_, kStreamSample, 3 * k)) * area / n;
      const size_t t = std::min<size_t>(std::upper_bound(cumulated.begin(), cumulated.end(), at) - cumulated.begin(),
                                        cumulated.size() - 1);
      const Eigen::Vector3i& tri = mesh.triangles[t];
      const Eigen::Vector3d a = mesh.vertices[tri[0]].cast<double>();
      const Eigen::Vector3d b = mesh.vertices[tri[1]].cast<double>();
      const Eigen::Vector3d c = mesh.vertices[tri[2]].cast<double>();
      const double r1 = std::sqrt(counterUniform(seed_, kStreamSample, 3 * k + 1));
      const double r2 = counterUniform(seed_, kStreamSample, 3 * k + 2);
      out.points[k] = ((1.0 - r1) * a + r1 * (1.0 - r2) * b + r1 * r2 * c).cast<float>();
      out.normals[k] = (b - a).cross(c - a).normalized().cast<float>();
      out.triangles[k] = static_cast<int>(t);
    }
  });
  *cloud = std::move(out);
  return Status::Ok();
}

}  // namespace surface_nbv
