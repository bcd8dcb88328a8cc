// Appends closed primitives to a TriangleMesh. Units are metres and radians,
// every argument is in the mesh's own frame (the world frame for scenes, Z up).
// Triangles are wound counter-clockwise seen from outside (normals outward),
// or seen from inside while setInward(true) is in effect (e.g. a room).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "surface_nbv/sensor/triangle_mesh.h"

namespace surface_nbv {

class MeshBuilder {
 public:
  MeshBuilder() = default;

  // While true, primitives added afterwards face inward (seen from inside).
  void setInward(bool inward) { inward_ = inward; }
  bool inward() const { return inward_; }

  // A box of full extents `size` centred at `center`, rotated by `yaw` about z.
  void addBox(const Eigen::Vector3d& center, const Eigen::Vector3d& size, double yaw = 0.0);
  // The axis-aligned box [lo, hi].
  void addAlignedBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
  // A box whose local axes are the columns of `rotation` (a reflection is
  // accepted and still gives outward normals).
  void addOrientedBox(const Eigen::Vector3d& center, const Eigen::Vector3d& half_extents,
                      const Eigen::Matrix3d& rotation);
  // A box from p0 to p1 (end faces centred on them): `width` across the
  // horizontal side direction, `height` across the remaining direction.
  void addBeam(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double width,
               double height);

  // A truncated cone from `base` (radius r0) to `top` (radius r1) with
  // `segments` sides (at least 3). A zero radius ends in a single apex vertex.
  // Without caps the two ends stay open. Nothing is added when base == top.
  void addFrustum(const Eigen::Vector3d& base, const Eigen::Vector3d& top, double r0, double r1,
                  int segments, bool capped = true);
  void addCylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& top, double radius,
                   int segments, bool capped = true);
  void addCone(const Eigen::Vector3d& base, const Eigen::Vector3d& apex, double radius,
               int segments);
  // A UV sphere with `rings` latitude bands (at least 2) and `segments`
  // longitude sides (at least 3); poles on the z axis through `center`.
  void addSphere(const Eigen::Vector3d& center, double radius, int rings, int segments);
  // A simple (possibly non-convex) polygon in the xy plane, either winding,
  // extruded from z0 to z1. Polygons with fewer than 3 points are ignored.
  void addPrism(const std::vector<Eigen::Vector2d>& polygon, double z0, double z1);

  const TriangleMesh& mesh() const { return mesh_; }
  // Moves the mesh out and leaves the builder empty.
  TriangleMesh take();
  // A copy of the mesh with every triangle's winding reversed.
  TriangleMesh flipped() const;

 private:
  int addVertex(const Eigen::Vector3d& p);
  void addTriangle(int a, int b, int c);
  void addQuad(int a, int b, int c, int d);
  // Corner i is on the +x side when bit 0 is set, +y for bit 1, +z for bit 2,
  // `reflect` reverses the winding (for a left-handed corner frame).
  void addBoxCorners(const std::array<Eigen::Vector3d, 8>& corners, bool reflect);

  TriangleMesh mesh_;
  bool inward_ = false;
};

// Indices (into `polygon`) of a triangulation of a simple polygon given
// counter-clockwise, by ear clipping; each triple is counter-clockwise.
std::vector<Eigen::Vector3i> triangulatePolygon(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace surface_nbv
