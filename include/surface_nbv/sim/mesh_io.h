// Mesh files in and out through assimp. Loading keeps the file's own up axis
// (a Z-up COLLADA file stays Z-up: ROS is Z-up) unless told the file is Y-up,
// applies the file's unit scale, then p' = scale * p + offset (or fits the
// model into a box), then clips the triangles to the crop box.
#pragma once

#include <string>

#include "surface_nbv/common.h"
#include "surface_nbv/sensor/triangle_mesh.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct MeshLoadOptions {
  // The model's up axis: "z" keeps it; "y" turns a Y-up model (as most OBJ
  // and glTF exports are) Z-up by +90 degrees about x, (x, y, z) -> (x, -z, y).
  std::string up_axis = "z";
  double scale = 1.0;
  // When set (every component > 0), the scale is chosen instead: the largest
  // uniform one that fits the model's bounding box into a box of this size,
  // its footprint centred on x = y = 0 and its base on z = 0 (the paper's
  // "scaled to fit in a box"; its statue is 20 x 20 x 60 m). `scale` must then
  // stay 1. The offset and the crop follow.
  Eigen::Vector3d fit_size = Eigen::Vector3d::Zero();
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  // Applied after scale and offset; the default (infinite) box keeps everything.
  AlignedBox crop{Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity()),
                  Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity())};

  Status validate() const;
  bool hasCrop() const { return (crop.min.array().isFinite() || crop.max.array().isFinite()).any(); }
  bool fitsToBox() const { return (fit_size.array() > 0.0).all(); }
};

// Applies the up axis, scale (or fit), offset and crop of `options` to `mesh`
// in place; returns the scale applied (the fit's, when fitting).
double applyLoadOptions(const MeshLoadOptions& options, TriangleMesh* mesh);

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
