#include "surface_nbv/sim/mesh_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include <Eigen/Geometry>

namespace surface_nbv {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// Unit vectors u, v with (u, v, axis) right-handed and orthonormal.
void orthonormalBasis(const Eigen::Vector3d& axis, Eigen::Vector3d* u, Eigen::Vector3d* v) {
  const Eigen::Vector3d helper =
      std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  *u = axis.cross(helper).normalized();
  *v = axis.cross(*u);
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double signedArea(const std::vector<Eigen::Vector2d>& polygon) {
  double sum = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    sum += cross2(polygon[i], polygon[(i + 1) % polygon.size()]);
  }
  return 0.5 * sum;
}

// True when p lies inside or on the counter-clockwise triangle abc.
bool inTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                const Eigen::Vector2d& c) {
  return cross2(b - a, p - a) >= 0.0 && cross2(c - b, p - b) >= 0.0 &&
         cross2(a - c, p - c) >= 0.0;
}

// Drops repeated and collinear points so every corner turns.
std::vector<Eigen::Vector2d> cleanPolygon(std::vector<Eigen::Vector2d> polygon) {
  double scale = 0.0;
  for (const Eigen::Vector2d& p : polygon) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  const double eps = 1e-12 * std::max(1.0, scale * scale);
  bool changed = true;
  while (changed && polygon.size() >= 3) {
    changed = false;
    for (size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector2d& prev = polygon[(i + polygon.size() - 1) % polygon.size()];
      const Eigen::Vector2d& next = polygon[(i + 1) % polygon.size()];
      const Eigen::Vector2d& cur = polygon[i];
      if ((cur - prev).squaredNorm() <= eps || std::abs(cross2(cur - prev, next - cur)) <= eps) {
        polygon.erase(polygon.begin() + static_cast<long>(i));
        changed = true;
        break;
      }
    }
  }
  return polygon;
}

}  // namespace

std::vector<Eigen::Vector3i> triangulatePolygon(const std::vector<Eigen::Vector2d>& polygon) {
  std::vector<Eigen::Vector3i> out;
  std::vector<int> remaining(polygon.size());
  for (size_t i = 0; i < polygon.size(); ++i) remaining[i] = static_cast<int>(i);
  while (remaining.size() > 3) {
    const size_t m = remaining.size();
    size_t ear = m;
    for (size_t i = 0; i < m && ear == m; ++i) {
      const int ia = remaining[(i + m - 1) % m], ib = remaining[i], ic = remaining[(i + 1) % m];
      const Eigen::Vector2d &a = polygon[ia], &b = polygon[ib], &c = polygon[ic];
      if (cross2(b - a, c - b) <= 0.0) continue;
      bool blocked = false;
      for (int j : remaining) {
        if (j == ia || j == ib || j == ic) continue;
        const Eigen::Vector2d& p = polygon[j];
        if (p == a || p == b || p == c) continue;
        if (inTriangle(p, a, b, c)) {
          blocked = true;
          break;
        }
      }
      if (!blocked) ear = i;
    }
    // A self-intersecting input may have no ear; clipping any corner still terminates.
    if (ear == m) ear = 0;
    out.emplace_back(remaining[(ear + m - 1) % m], remaining[ear], remaining[(ear + 1) % m]);
    remaining.erase(remaining.begin() + static_cast<long>(ear));
  }
  if (remaining.size() == 3) out.emplace_back(remaining[0], remaining[1], remaining[2]);
  return out;
}

int MeshBuilder::addVertex(const Eigen::Vector3d& p) {
  mesh_.vertices.push_back(p.cast<float>());
  return static_cast<int>(mesh_.vertices.size()) - 1;
}

void MeshBuilder::addTriangle(int a, int b, int c) {
  if (inward_) std::swap(b, c);
  mesh_.triangles.emplace_back(a, b, c);
}

void MeshBuilder::addQuad(int a, int b, int c, int d) {
  addTriangle(a, b, c);
  addTriangle(a, c, d);
}

void MeshBuilder::addBox(const Eigen::Vector3d& center, const Eigen::Vector3d& size, double yaw) {
  if (yaw == 0.0) {
    addAlignedBox(center - 0.5 * size.cwiseAbs(), center + 0.5 * size.cwiseAbs());
    return;
  }
  addOrientedBox(center, 0.5 * size.cwiseAbs(),
                 Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix());
}

void MeshBuilder::addAlignedBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const Eigen::Vector3d a = lo.cwiseMin(hi), b = lo.cwiseMax(hi);
  std::array<Eigen::Vector3d, 8> corners;
  for (int i = 0; i < 8; ++i) {
    corners[i] = Eigen::Vector3d((i & 1) ? b.x() : a.x(), (i & 2) ? b.y() : a.y(),
                                 (i & 4) ? b.z() : a.z());
  }
  addBoxCorners(corners, false);
}

void MeshBuilder::addOrientedBox(const Eigen::Vector3d& center,
                                 const Eigen::Vector3d& half_extents,
                                 const Eigen::Matrix3d& rotation) {
  std::array<Eigen::Vector3d, 8> corners;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d local((i & 1) ? half_extents.x() : -half_extents.x(),
                                (i & 2) ? half_extents.y() : -half_extents.y(),
                                (i & 4) ? half_extents.z() : -half_extents.z());
    corners[i] = center + rotation * local;
  }
  addBoxCorners(corners, rotation.determinant() < 0.0);
}

void MeshBuilder::addBoxCorners(const std::array<Eigen::Vector3d, 8>& corners, bool reflect) {
  // Corner i is on the +x side when bit 0 is set, +y for bit 1, +z for bit 2.
  static const std::array<std::array<int, 4>, 6> kFaces = {{{0, 4, 6, 2},
                                                             {1, 3, 7, 5},
                                                             {0, 1, 5, 4},
                                                             {2, 6, 7, 3},
                                                             {0, 2, 3, 1},
                                                             {4, 5, 7, 6}}};
  const int base = static_cast<int>(mesh_.vertices.size());
  for (const Eigen::Vector3d& c : corners) addVertex(c);
  for (const std::array<int, 4>& f : kFaces) {
    if (reflect) {
      addQuad(base + f[0], base + f[3], base + f[2], base + f[1]);
    } else {
      addQuad(base + f[0], base + f[1], base + f[2], base + f[3]);
    }
  }
}

void MeshBuilder::addBeam(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double width,
                          double height) {
  const Eigen::Vector3d axis = p1 - p0;
  const double length = axis.norm();
  if (length <= 0.0) return;
  const Eigen::Vector3d d = axis / length;
  Eigen::Vector3d side = Eigen::Vector3d::UnitZ().cross(d);
  if (side.norm() < 1e-9) side = d.cross(Eigen::Vector3d::UnitX());
  side.normalize();
  Eigen::Matrix3d rotation;
  rotation.col(0) = d;
  rotation.col(1) = side;
  rotation.col(2) = d.cross(side);
  addOrientedBox(0.5 * (p0 + p1), Eigen::Vector3d(0.5 * length, 0.5 * width, 0.5 * height),
                 rotation);
}

void MeshBuilder::addFrustum(const Eigen::Vector3d& base, const Eigen::Vector3d& top, double r0,
                             double r1, int segments, bool capped) {
  const Eigen::Vector3d axis = top - base;
  r0 = std::max(0.0, r0);
  r1 = std::max(0.0, r1);
  if (axis.norm() <= 0.0 || (r0 == 0.0 && r1 == 0.0)) return;
  const int n = std::max(3, segments);
  Eigen::Vector3d u, v;
  orthonormalBasis(axis.normalized(), &u, &v);

  // A ring of n vertices, or a single apex vertex when the radius is zero.
  auto ring = [&](const Eigen::Vector3d& c, double r) {
    const int first = static_cast<int>(mesh_.vertices.size());
    if (r == 0.0) {
      addVertex(c);
      return first;
    }
    for (int i = 0; i < n; ++i) {
      const double t = kTwoPi * i / n;
      addVertex(c + r * (std::cos(t) * u + std::sin(t) * v));
    }
    return first;
  };
  const int b = ring(base, r0);
  const int t = ring(top, r1);
  auto bi = [&](int i) { return r0 == 0.0 ? b : b + i % n; };
  auto ti = [&](int i) { return r1 == 0.0 ? t : t + i % n; };
  for (int i = 0; i < n; ++i) {
    if (r0 == 0.0) {
      addTriangle(b, ti(i + 1), ti(i));
    } else if (r1 == 0.0) {
      addTriangle(bi(i), bi(i + 1), t);
    } else {
      addQuad(bi(i), bi(i + 1), ti(i + 1), ti(i));
    }
  }
  if (!capped) return;
  if (r0 > 0.0) {
    const int c = addVertex(base);
    for (int i = 0; i < n; ++i) addTriangle(c, bi(i + 1), bi(i));
  }
  if (r1 > 0.0) {
    const int c = addVertex(top);
    for (int i = 0; i < n; ++i) addTriangle(c, ti(i), ti(i + 1));
  }
}

void MeshBuilder::addCylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& top,
                              double radius, int segments, bool capped) {
  addFrustum(base, top, radius, radius, segments, capped);
}

void MeshBuilder::addCone(const Eigen::Vector3d& base, const Eigen::Vector3d& apex, double radius,
                          int segments) {
  addFrustum(base, apex, radius, 0.0, segments, true);
}

void MeshBuilder::addSphere(const Eigen::Vector3d& center, double radius, int rings,
                            int segments) {
  if (radius <= 0.0) return;
  const int nr = std::max(2, rings);
  const int n = std::max(3, segments);
  const int north = addVertex(center + Eigen::Vector3d(0.0, 0.0, radius));
  const int first_ring = static_cast<int>(mesh_.vertices.size());
  for (int k = 1; k < nr; ++k) {
    const double phi = M_PI * k / nr;
    const double z = radius * std::cos(phi), rho = radius * std::sin(phi);
    for (int i = 0; i < n; ++i) {
      const double t = kTwoPi * i / n;
      addVertex(center + Eigen::Vector3d(rho * std::cos(t), rho * std::sin(t), z));
    }
  }
  const int south = addVertex(center - Eigen::Vector3d(0.0, 0.0, radius));
  auto at = [&](int k, int i) { return first_ring + (k - 1) * n + i % n; };
  for (int i = 0; i < n; ++i) {
    addTriangle(north, at(1, i), at(1, i + 1));
    for (int k = 1; k + 1 < nr; ++k) {
      addQuad(at(k + 1, i), at(k + 1, i + 1), at(k, i + 1), at(k, i));
    }
    addTriangle(south, at(nr - 1, i + 1), at(nr - 1, i));
  }
}

void MeshBuilder::addPrism(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1) {
  std::vector<Eigen::Vector2d> poly = cleanPolygon(polygon);
  if (poly.size() < 3 || z0 == z1) return;
  if (signedArea(poly) < 0.0) std::reverse(poly.begin(), poly.end());
  if (z1 < z0) std::swap(z0, z1);
  const int n = static_cast<int>(poly.size());
  const int b = static_cast<int>(mesh_.vertices.size());
  for (const Eigen::Vector2d& p : poly) addVertex(Eigen::Vector3d(p.x(), p.y(), z0));
  const int t = static_cast<int>(mesh_.vertices.size());
  for (const Eigen::Vector2d& p : poly) addVertex(Eigen::Vector3d(p.x(), p.y(), z1));
  for (int i = 0; i < n; ++i) addQuad(b + i, b + (i + 1) % n, t + (i + 1) % n, t + i);
  for (const Eigen::Vector3i& tri : triangulatePolygon(poly)) {
    addTriangle(t + tri[0], t + tri[1], t + tri[2]);
    addTriangle(b + tri[0], b + tri[2], b + tri[1]);
  }
}

TriangleMesh MeshBuilder::take() {
  TriangleMesh out = std::move(mesh_);
  mesh_ = TriangleMesh();
  return out;
}

TriangleMesh MeshBuilder::flipped() const {
  TriangleMesh out = mesh_;
  for (Eigen::Vector3i& t : out.triangles) std::swap(t[1], t[2]);
  return out;
}

}  // namespace surface_nbv
