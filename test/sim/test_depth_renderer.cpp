// Depth rendering against analytic geometry: planes, spheres, corners, range and FOV limits.
#include "render_test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

namespace surface_nbv {
namespace {

using Eigen::Vector3d;
using namespace render_test;

TEST(DepthRenderer, FrontoParallelPlaneReadsExactDepthEverywhere) {
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  const CameraConfig config;
  for (int threads : {1, 2, 3}) {
    const DepthImage image = render(*scene, config, Transform::Identity(), threads);
    ASSERT_EQ(image.width, 640);
    ASSERT_EQ(image.height, 480);
    ASSERT_EQ(image.data.size(), 640u * 480u);
    EXPECT_EQ(image.validCount(), 640u * 480u) << threads << " threads";
    EXPECT_EQ(countOff(image, 5.0, 1e-5), 0u) << threads << " threads";
    EXPECT_NEAR(image.at(0, 0), 5.0, 1e-5);
    EXPECT_NEAR(image.at(479, 639), 5.0, 1e-5);
  }
}

TEST(DepthRenderer, WidthNotAMultipleOfThePacketSize) {
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  for (int width : {1, 7, 9, 101}) {
    CameraConfig config;
    config.width = width;
    config.height = 13;
    for (int threads : {1, 2}) {
      const DepthImage image = render(*scene, config, Transform::Identity(), threads);
      ASSERT_EQ(image.width, width);
      ASSERT_EQ(image.data.size(), static_cast<size_t>(width) * 13);
      EXPECT_EQ(countOff(image, 5.0, 1e-5), 0u) << "width " << width << ", " << threads << " threads";
    }
  }
}

// Packets of 4, 8 and 16 rays trace the same rays: the images agree bit for
// bit (the mission's flights do not depend on the CPU's packet width), on the
// statue from poses that see edges, ledges and empty sky, and on an odd size.
TEST(DepthRenderer, EveryPacketWidthRendersTheSameImage) {
  TriangleMesh mesh;
  ASSERT_TRUE(makeProceduralScene("statue", &mesh).ok());
  const auto scene = buildScene(mesh);
  ASSERT_NE(scene, nullptr);
  const int native = DepthRenderer(*scene, DepthCamera(CameraConfig())).packetWidth();
  EXPECT_EQ(native, scene->nativePacketWidth());
  EXPECT_TRUE(native == 4 || native == 8 || native == 16) << native;
  EXPECT_EQ(DepthRenderer(*scene, DepthCamera(CameraConfig()), 1, 12).packetWidth(), native);
  const Transform poses[] = {lookAlong(Vector3d(-14, 0, 3), Vector3d::UnitX()),
                             lookAlong(Vector3d(-9.5, -9.5, 18.5), Vector3d(1, 1, -0.6)),
                             lookAlong(Vector3d(6, -3, 47), Vector3d(-1, 0.4, 0.3))};
  for (const CameraConfig& config : {CameraConfig(), oddCamera()}) {
    for (const Transform& T : poses) {
      DepthImage four;
      DepthRenderer(*scene, DepthCamera(config), 2, 4).render(T, &four);
      ASSERT_GT(four.validCount(), four.data.size() / 10);
      ASSERT_LT(four.validCount(), four.data.size());
      for (int width : {8, 16}) {
        const DepthRenderer renderer(*scene, DepthCamera(config), 2, width);
        ASSERT_EQ(renderer.packetWidth(), width);
        DepthImage image;
        renderer.render(T, &image);
        // No NaN to compare: misses are +-Inf (REP 117), equal to themselves.
        EXPECT_TRUE(image.data == four.data) << "packet " << width << ", " << config.width << " px";
      }
    }
  }
}

// The renderer forms each frame's rays from per-column and per-row products
// (depth_renderer.cpp). Traced as 2 x 2 packets of R * Vector3d(x, y, 1), each
// ray's direction straight from Eigen's product, the statue gives the same
// images bit for bit, from poses of every kind of rotation.
TEST(DepthRenderer, RaysAreTheRotatedPixelRays) {
  TriangleMesh mesh;
  ASSERT_TRUE(makeProceduralScene("statue", &mesh).ok());
  const auto scene = buildScene(mesh);
  ASSERT_NE(scene, nullptr);
  const Transform poses[] = {lookAlong(Vector3d(-14, 0, 3), Vector3d::UnitX()),
                             lookAlong(Vector3d(-9.5, -9.5, 18.5), Vector3d(1, 1, -0.6)),
                             lookAlong(Vector3d(6, -3, 47), Vector3d(-1, 0.4, 0.3)),
                             lookAlong(Vector3d(3, 12, 30), Vector3d(-0.2, -1, -0.1), Vector3d(0.3, 0, 1))};
  for (const CameraConfig& config : {CameraConfig(), oddCamera()}) {
    const DepthCamera camera(config);
    for (const Transform& T : poses) {
      DepthImage image;
      DepthRenderer(*scene, camera, 2, 4).render(T, &image);
      ASSERT_GT(image.validCount(), image.data.size() / 50);
      const Eigen::Matrix3d R = T.linear();
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      size_t differ = 0;
      for (int row0 = 0; row0 < config.height; row0 += 2) {
        for (int col0 = 0; col0 < config.width; col0 += 2) {
          alignas(16) RTCRayHit4 packet;
          alignas(16) int valid[4];
          for (int k = 0; k < 4; ++k) {
            const int row = std::min(row0 + k / 2, config.height - 1), col = std::min(col0 + k % 2, config.width - 1);
            valid[k] = row0 + k / 2 < config.height && col0 + k % 2 < config.width ? -1 : 0;
            const Vector3d d = R * Vector3d(camera.pixelRay(col, 0).x(), camera.pixelRay(0, row).y(), 1.0);
            packet.ray.org_x[k] = static_cast<float>(T.translation().x());
            packet.ray.org_y[k] = static_cast<float>(T.translation().y());
            packet.ray.org_z[k] = static_cast<float>(T.translation().z());
            packet.ray.dir_x[k] = static_cast<float>(d.x());
            packet.ray.dir_y[k] = static_cast<float>(d.y());
            packet.ray.dir_z[k] = static_cast<float>(d.z());
            packet.ray.tnear[k] = 0.0f;
            packet.ray.tfar[k] = static_cast<float>(config.max_range);
            packet.ray.time[k] = 0.0f;
            packet.ray.mask[k] = 0xFFFFFFFFu;
            packet.ray.id[k] = static_cast<unsigned>(k);
            packet.ray.flags[k] = 0;
            packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
          }
          rtcIntersect4(valid, scene->handle(), &context, &packet);
          for (int k = 0; k < 4; ++k) {
            if (!valid[k]) continue;
            float z = std::numeric_limits<float>::infinity();
            if (packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) {
              z = packet.ray.tfar[k];
              if (z < static_cast<float>(config.min_range)) z = -std::numeric_limits<float>::infinity();
            }
            differ += image.at(row0 + k / 2, col0 + k % 2) != z ? 1 : 0;
          }
        }
      }
      EXPECT_EQ(differ, 0u) << config.width << " px";
    }
  }
}

TEST(DepthRenderer, RotatedCameraAboveGroundPlane) {
  // World ground plane z = 0.75; camera 5 m above it looking straight down
  // with an arbitrary yaw and horizontal position.
  TriangleMesh mesh;
  addQuad(&mesh, Vector3d(10, -20, 0.75), Vector3d(50, 0, 0), Vector3d(0, 50, 0));
  const auto scene = buildScene(mesh);
  ASSERT_NE(scene, nullptr);
  for (double yaw : {0.0, 0.4, 2.1, -2.9}) {
    const Transform T =
        lookAlong(Vector3d(12.3, -17.9, 5.75), -Vector3d::UnitZ(), Vector3d(std::cos(yaw), std::sin(yaw), 0));
    ASSERT_NEAR(T.linear().determinant(), 1.0, 1e-12);
    for (int threads : {1, 2}) {
      const DepthImage image = render(*scene, CameraConfig(), T, threads);
      EXPECT_EQ(countOff(image, 5.0, 1e-5), 0u) << "yaw " << yaw << ", " << threads << " threads";
    }
  }
}

TEST(DepthRenderer, RotatedCameraFacingVerticalWall) {
  for (double yaw : {0.3, 1.9, -1.2}) {
    const Vector3d forward(std::cos(yaw), std::sin(yaw), 0.0);
    const Vector3d side(-std::sin(yaw), std::cos(yaw), 0.0);
    const Vector3d camera(-3.2, 4.4, 1.7);
    TriangleMesh mesh;
    addQuad(&mesh, camera + 5.0 * forward, 10.0 * side, Vector3d(0, 0, 10));
    const auto scene = buildScene(mesh);
    ASSERT_NE(scene, nullptr);
    const Transform T = lookAlong(camera, forward);
    for (int threads : {1, 2}) {
      const DepthImage image = render(*scene, CameraConfig(), T, threads);
      EXPECT_EQ(countOff(image, 5.0, 1e-5), 0u) << "yaw " << yaw << ", " << threads << " threads";
    }
  }
}

TEST(DepthRenderer, EmptyViewIsAllNaNAndImageIsResized) {
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  DepthImage image;
  image.resize(3, 2);
  image.data.assign(6, 1.0f);
  // Looking away from the plane.
  const DepthRenderer renderer(*scene, DepthCamera(CameraConfig()), 2);
  renderer.render(lookAlong(Vector3d::Zero(), -Vector3d::UnitZ(), Vector3d::UnitX()), &image);
  EXPECT_EQ(image.width, 640);
  EXPECT_EQ(image.height, 480);
  EXPECT_EQ(image.data.size(), 640u * 480u);
  EXPECT_EQ(image.validCount(), 0u);
}

TEST(DepthRenderer, ThreadCountIsAtLeastOne) {
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  const DepthCamera camera{CameraConfig()};
  EXPECT_EQ(DepthRenderer(*scene, camera, 0).threads(), 1);
  EXPECT_EQ(DepthRenderer(*scene, camera, -3).threads(), 1);
  EXPECT_EQ(DepthRenderer(*scene, camera, 4).threads(), 4);
  const DepthImage image = render(*scene, CameraConfig(), Transform::Identity(), 0);
  EXPECT_EQ(countOff(image, 5.0, 1e-5), 0u);
}

// ---- (b) a tilted plane ----


TEST(DepthRenderer, TiltedPlaneMatchesAnalyticIntersection) {
  const TiltedPlane plane;
  const CameraConfig config;
  const DepthCamera cam(config);
  Transform moved = Transform::Identity();
  moved.linear() = Eigen::AngleAxisd(0.7, Vector3d(0.2, -1.0, 0.4).normalized()).toRotationMatrix();
  moved.translation() = Vector3d(3.5, -1.25, 2.0);
  for (const Transform& T_W_C : {Transform::Identity(), moved}) {
    const auto scene = buildScene(plane.mesh(T_W_C));
    ASSERT_NE(scene, nullptr);
    const DepthImage image = render(*scene, config, T_W_C, 2);
    size_t compared = 0, nan_expected = 0;
    double min_depth = 1e9, max_depth = 0.0;
    for (int row = 0; row < cam.height(); ++row) {
      for (int col = 0; col < cam.width(); ++col) {
        const double t = plane.depth(cam, col, row);
        const float z = image.at(row, col);
        if (t >= config.min_range + 1e-3 && t <= config.max_range - 1e-3) {
          ASSERT_TRUE(std::isfinite(z)) << col << " " << row << " expected " << t;
          ASSERT_NEAR(z, t, 1e-4) << col << " " << row;
          min_depth = std::min(min_depth, t);
          max_depth = std::max(max_depth, t);
          ++compared;
        } else if (t > config.max_range + 1e-3) {
          ASSERT_TRUE(std::isinf(z) && z > 0) << col << " " << row << " beyond range (REP 117 +Inf), got " << z;
          ++nan_expected;
        }
      }
    }
    // The tilt spreads depths over the whole range and beyond it.
    EXPECT_GT(compared, 200000u);
    EXPECT_GT(nan_expected, 10000u);
    EXPECT_LT(min_depth, 3.5);
    EXPECT_GT(max_depth, 7.9);
  }
}

// ---- (c) a sphere ----

// Smaller root of |o + t w - c| = r, or NaN on a miss.
double raySphere(const Vector3d& o, const Vector3d& w, const Vector3d& c, double r) {
  const Vector3d oc = o - c;
  const double a = w.squaredNorm(), b = oc.dot(w), q = oc.squaredNorm() - r * r;
  const double disc = b * b - a * q;
  if (disc < 0.0) return std::nan("");
  return (-b - std::sqrt(disc)) / a;
}

TEST(DepthRenderer, SphereDepthWithinTessellationError) {
  const Vector3d center(1.0, 2.0, 3.0);
  const double r = 1.0;
  const int rings = 128, segments = 256;
  MeshBuilder b;
  b.addSphere(center, r, rings, segments);
  const auto scene = buildScene(b.mesh());
  ASSERT_NE(scene, nullptr);
  // Every triangle spans at most this angle between its vertices, so every
  // point on it is at least r cos(alpha) from the centre and at most r.
  const double alpha = M_PI / rings + 2.0 * M_PI / segments;
  const double r_in = r * std::cos(alpha);

  const CameraConfig config = oddCamera();
  const DepthCamera cam(config);
  const double distance = 5.0;
  const Vector3d view_dir = Vector3d(-0.6, 0.3, -0.5).normalized();
  const Transform T = lookAlong(center - distance * view_dir, view_dir);
  const DepthImage image = render(*scene, config, T, 2);

  // The centre pixel looks at the sphere centre.
  ASSERT_DOUBLE_EQ(cam.cx(), 80.0);
  ASSERT_DOUBLE_EQ(cam.cy(), 60.0);
  const float zc = image.at(60, 80);
  EXPECT_GE(zc, distance - r - 1e-5);
  EXPECT_LE(zc, distance - r_in + 1e-5);
  EXPECT_LT(r - r_in, 3e-3);

  size_t inside = 0, outside = 0, band = 0;
  for (int row = 0; row < cam.height(); ++row) {
    for (int col = 0; col < cam.width(); ++col) {
      const Vector3d w = T.linear() * cam.pixelRay(col, row);
      const double t_outer = raySphere(T.translation(), w, center, r);
      const double t_inner = raySphere(T.translation(), w, center, r_in);
      const float z = image.at(row, col);
      if (std::isnan(t_outer)) {
        ASSERT_TRUE(std::isinf(z) && z > 0) << "silhouette leak at " << col << " " << row << ": " << z;
        ++outside;
      } else if (!std::isnan(t_inner)) {
        ASSERT_TRUE(std::isfinite(z)) << col << " " << row;
        ASSERT_GE(z, t_outer - 1e-5) << col << " " << row;
        ASSERT_LE(z, t_inner + 1e-5) << col << " " << row;
        ++inside;
      } else {
        ++band;
      }
    }
  }
  // The sphere subtends asin(1/5) = 11.5 deg: a disc of radius tan(11.5 deg)
  // on the z = 1 plane, an ellipse of pi fx fy tan^2 = 1104 pixels.
  const double tan_half = std::tan(std::asin(r / distance));
  EXPECT_NEAR(static_cast<double>(inside), M_PI * cam.fx() * cam.fy() * tan_half * tan_half, 60.0);
  EXPECT_LT(band, 60u);
  EXPECT_EQ(inside + outside + band, 161u * 121u);
  EXPECT_EQ(image.validCount() >= inside, true);
  EXPECT_LE(image.validCount(), inside + band);
}

// ---- (d) a cube corner ----

TEST(DepthRenderer, CubeCornerFacesMatchAnalyticPlanes) {
  const Vector3d lo(0, 0, 0), hi(2, 2, 2);
  MeshBuilder b;
  b.addAlignedBox(lo, hi);
  const auto scene = buildScene(b.mesh());
  ASSERT_NE(scene, nullptr);
  const CameraConfig config;
  const DepthCamera cam(config);
  const Transform T = lookAlong(Vector3d(4.5, 4.5, 4.5), Vector3d(-1, -1, -1));
  const DepthImage image = render(*scene, config, T, 2);
  const Vector3d o = T.translation();

  int per_face[3] = {0, 0, 0};
  size_t misses = 0;
  const double edge = 2e-3;
  for (int row = 0; row < cam.height(); ++row) {
    for (int col = 0; col < cam.width(); ++col) {
      const Vector3d w = T.linear() * cam.pixelRay(col, row);
      // The ray meets the faces x = 2, y = 2, z = 2 (those facing the camera).
      int face = -1;
      double t_hit = 0.0;
      bool near_edge = false, near_box = false;
      for (int axis = 0; axis < 3; ++axis) {
        const double t = (hi[axis] - o[axis]) / w[axis];
        const Vector3d p = o + t * w;
        bool in = true, in_grown = true;
        for (int k = 0; k < 3; ++k) {
          if (k == axis) continue;
          in = in && p[k] >= lo[k] && p[k] <= hi[k];
          in_grown = in_grown && p[k] >= lo[k] - edge && p[k] <= hi[k] + edge;
          near_edge = near_edge || (in_grown && (std::abs(p[k] - lo[k]) < edge || std::abs(p[k] - hi[k]) < edge));
        }
        near_box = near_box || in_grown;
        if (in) {
          face = axis;
          t_hit = t;
        }
      }
      const float z = image.at(row, col);
      if (near_edge) continue;
      if (face < 0) {
        if (!near_box) {
          ASSERT_TRUE(std::isinf(z) && z > 0) << col << " " << row << ": " << z;
          ++misses;
        }
        continue;
      }
      ASSERT_TRUE(std::isfinite(z)) << col << " " << row;
      ASSERT_NEAR(z, t_hit, 1e-4) << "face " << face << " pixel " << col << " " << row;
      ++per_face[face];
    }
  }
  // The corner (2, 2, 2) is on the optical axis at 2.5 sqrt(3) m.
  EXPECT_NEAR(image.at(239, 319), 2.5 * std::sqrt(3.0), 0.02);
  // The view is threefold symmetric about the optical axis, so the three faces
  // cover equal areas of the z = 1 plane and nearly equal pixel counts.
  const double mean = (per_face[0] + per_face[1] + per_face[2]) / 3.0;
  EXPECT_GT(mean, 8000.0);
  for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(per_face[axis], mean, 0.02 * mean) << "face " << axis;
  EXPECT_GT(misses, 100000u);
}

// ---- (e) range limits ----

TEST(DepthRenderer, PlaneCloserThanMinRangeIsNotSeen) {
  const auto scene = buildScene(planeAtZ(1.0));
  ASSERT_NE(scene, nullptr);
  EXPECT_EQ(render(*scene, CameraConfig(), Transform::Identity()).validCount(), 0u);
}

TEST(DepthRenderer, ObjectCloserThanMinRangeOccludesTheWallBehind) {
  TriangleMesh mesh = planeAtZ(6.0);
  // A 0.6 x 0.6 m plate at 1 m: |x / z| and |y / z| up to 0.3.
  addQuad(&mesh, Vector3d(0, 0, 1.0), Vector3d(0.3, 0, 0), Vector3d(0, 0.3, 0));
  const auto scene = buildScene(mesh);
  ASSERT_NE(scene, nullptr);
  const CameraConfig config;
  const DepthCamera cam(config);
  for (int threads : {1, 2}) {
    const DepthImage image = render(*scene, config, Transform::Identity(), threads);
    size_t nan_inside = 0;
    for (int row = 0; row < cam.height(); ++row) {
      for (int col = 0; col < cam.width(); ++col) {
        const Vector3d ray = cam.pixelRay(col, row);
        const float z = image.at(row, col);
        if (std::abs(ray.x()) < 0.3 && std::abs(ray.y()) < 0.3) {
          ASSERT_TRUE(std::isinf(z) && z < 0) << "saw through the plate at " << col << " " << row << ": " << z;
          ++nan_inside;
        } else {
          ASSERT_NEAR(z, 6.0, 1e-5) << col << " " << row;
        }
      }
    }
    // Columns 224..415 and rows 115..364.
    EXPECT_EQ(nan_inside, 192u * 250u);
    EXPECT_EQ(image.validCount(), 640u * 480u - 192u * 250u);
  }
}

TEST(DepthRenderer, PlaneBeyondMaxRangeIsNotSeen) {
  const auto scene = buildScene(planeAtZ(9.0));
  ASSERT_NE(scene, nullptr);
  EXPECT_EQ(render(*scene, CameraConfig(), Transform::Identity()).validCount(), 0u);
  const auto just_beyond = buildScene(planeAtZ(8.01));
  ASSERT_NE(just_beyond, nullptr);
  EXPECT_EQ(render(*just_beyond, CameraConfig(), Transform::Identity()).validCount(), 0u);
}

TEST(DepthRenderer, PlanesJustInsideTheRangeAreSeen) {
  for (double z : {7.99, 1.61}) {
    const auto scene = buildScene(planeAtZ(z));
    ASSERT_NE(scene, nullptr);
    const DepthImage image = render(*scene, CameraConfig(), Transform::Identity());
    EXPECT_EQ(image.validCount(), 640u * 480u) << z;
    EXPECT_EQ(countOff(image, z, 1e-5), 0u) << z;
  }
}

TEST(DepthRenderer, CustomRangeIsApplied) {
  const auto scene = buildScene(planeAtZ(5.0));
  ASSERT_NE(scene, nullptr);
  CameraConfig config;
  config.max_range = 4.5;
  EXPECT_EQ(render(*scene, config, Transform::Identity()).validCount(), 0u);
  config.max_range = 20.0;
  config.min_range = 5.5;
  EXPECT_EQ(render(*scene, config, Transform::Identity()).validCount(), 0u);
  config.min_range = 0.0;
  EXPECT_EQ(countOff(render(*scene, config, Transform::Identity()), 5.0, 1e-5), 0u);
}

// ---- (f) FOV edges ----

// A wall at z = 6 and two thin plates at z = 4 facing the camera: one whose
// tangent range [0.997, 0.9995] holds only the outermost pixel ray (tangent
// 319.5 / 320 = 0.9984) on the `inside_sign` side, one just outside the FOV
// (tangent [1.0005, 1.05]) on the other side. `axis` 0 puts them at the left
// and right image edges, 1 at the top and bottom.
TriangleMesh fovEdgeScene(int axis, double inside_sign, double edge_tan) {
  TriangleMesh mesh = planeAtZ(6.0);
  const int other = 1 - axis;
  auto plate = [&](double tan0, double tan1) {
    Vector3d c(0, 0, 4.0), a = Vector3d::Zero(), b = Vector3d::Zero();
    c[axis] = 4.0 * 0.5 * (tan0 + tan1);
    a[axis] = 4.0 * 0.5 * (tan1 - tan0);
    b[other] = 0.4;
    addQuad(&mesh, c, a, b);
  };
  plate(inside_sign * 0.997 * edge_tan, inside_sign * 0.9995 * edge_tan);
  plate(-inside_sign * 1.0005 * edge_tan, -inside_sign * 1.05 * edge_tan);
  return mesh;
}

TEST(DepthRenderer, HorizontalFovEdgeColumns) {
  const CameraConfig config;
  const DepthCamera cam(config);
  const int w = cam.width();
  for (double sign : {1.0, -1.0}) {
    const auto scene = buildScene(fovEdgeScene(0, sign, 1.0));
    ASSERT_NE(scene, nullptr);
    const DepthImage image = render(*scene, config, Transform::Identity(), 2);
    const int edge = sign > 0 ? w - 1 : 0;
    const int next = sign > 0 ? w - 2 : 1;
    const int far_edge = sign > 0 ? 0 : w - 1;
    // The plates span |y / z| <= 0.1: rows 198..281.
    size_t plate_pixels = 0;
    for (int row = 0; row < cam.height(); ++row) {
      const bool on_plate = std::abs(cam.pixelRay(0, row).y()) < 0.1;
      EXPECT_NEAR(image.at(row, edge), on_plate ? 4.0 : 6.0, 1e-5) << "row " << row << " sign " << sign;
      EXPECT_NEAR(image.at(row, next), 6.0, 1e-5) << "row " << row;
      EXPECT_NEAR(image.at(row, far_edge), 6.0, 1e-5) << "row " << row;
      plate_pixels += on_plate ? 1 : 0;
    }
    EXPECT_EQ(plate_pixels, 84u);
    EXPECT_EQ(image.validCount(), 640u * 480u);
    EXPECT_EQ(countOff(image, 6.0, 1e-5), 84u) << "only the edge column sees a plate";
  }
}

TEST(DepthRenderer, VerticalFovEdgeRows) {
  const CameraConfig config;
  const DepthCamera cam(config);
  const int h = cam.height();
  const double edge_tan = std::tan(30.0 * M_PI / 180.0);
  // The outermost row ray has tangent 239.5 / fy = 0.99792 tan(30 deg), the
  // next one 0.99375 tan(30 deg): only the outermost one meets the plate.
  ASSERT_GT(std::abs(cam.pixelRay(0, h - 1).y()), 0.997 * edge_tan);
  ASSERT_LT(std::abs(cam.pixelRay(0, h - 2).y()), 0.997 * edge_tan);
  for (double sign : {1.0, -1.0}) {
    const auto scene = buildScene(fovEdgeScene(1, sign, edge_tan));
    ASSERT_NE(scene, nullptr);
    const DepthImage image = render(*scene, config, Transform::Identity(), 2);
    const int edge = sign > 0 ? h - 1 : 0;
    const int next = sign > 0 ? h - 2 : 1;
    const int far_edge = sign > 0 ? 0 : h - 1;
    size_t plate_pixels = 0;
    for (int col = 0; col < cam.width(); ++col) {
      const bool on_plate = std::abs(cam.pixelRay(col, 0).x()) < 0.1;
      EXPECT_NEAR(image.at(edge, col), on_plate ? 4.0 : 6.0, 1e-5) << "col " << col << " sign " << sign;
      EXPECT_NEAR(image.at(next, col), 6.0, 1e-5) << "col " << col;
      EXPECT_NEAR(image.at(far_edge, col), 6.0, 1e-5) << "col " << col;
      plate_pixels += on_plate ? 1 : 0;
    }
    EXPECT_EQ(plate_pixels, 64u);
    EXPECT_EQ(countOff(image, 6.0, 1e-5), 64u);
  }
}
}  // namespace
}  // namespace surface_nbv
