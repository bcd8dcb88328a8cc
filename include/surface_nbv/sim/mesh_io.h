// Mesh files in and out through assimp. Loading keeps the file's own up axis
// (a Z-up COLLADA file stays Z-up: ROS is Z-up), applies the file's unit scale,
// then p' = scale * p + offset, then clips the triangles to the crop box.
#pragma once

#include <string>

#include "surface_nbv/common.h"
#include "surface_nbv/sim/triangle_mesh.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct MeshLoadOptions {
  double scale = 1.0;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  // Applied after scale and offset; the default (infinite) box keeps everything.
  AlignedBox crop{Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity()),
                  Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity())};

  Status validate() const;
  bool hasCrop() const { return (crop.min.array().isFinite() || crop.max.array().isFinite()).any(); }
};

// Applies scale, offset and crop of `options` to `mesh` in place.
void applyLoadOptions(const MeshLoadOptions& options, TriangleMesh* mesh);

// Loads any mesh assimp reads (.dae, .stl, .obj, .ply, ...). A missing,
// unreadable or empty file (or one left empty by the crop) is an error that
// names the file; `mesh` is left unchanged then.
Status loadMesh(const std::string& path, const MeshLoadOptions& options, TriangleMesh* mesh);

// Writes `mesh` with assimp; the format follows the extension: .ply (binary),
// .stl (binary). The file is written to a temporary name and renamed.
Status saveMesh(const TriangleMesh& mesh, const std::string& path);

// Clips every triangle to `box` (Sutherland-Hodgman against its six planes)
// and re-triangulates the pieces, so a wall crossing the box is cut at the
// box face rather than dropped.
TriangleMesh cropMesh(const TriangleMesh& mesh, const AlignedBox& box);

}  // namespace surface_nbv
