#include "surface_nbv/sim/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

namespace surface_nbv {
namespace {

bool fileReadable(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return static_cast<bool>(in);
}

std::string lowerExtension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

using Polygon = std::vector<Eigen::Vector3d>;

// Keeps the part of `poly` where sign * (p[axis] - bound) <= 0.
Polygon clipAgainstPlane(const Polygon& poly, int axis, double bound, double sign) {
  Polygon out;
  const size_t n = poly.size();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = poly[i];
    const Eigen::Vector3d& b = poly[(i + 1) % n];
    const double da = sign * (a[axis] - bound);
    const double db = sign * (b[axis] - bound);
    if (da <= 0.0) out.push_back(a);
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
      const double t = da / (da - db);
      Eigen::Vector3d p = a + t * (b - a);
      p[axis] = bound;
      out.push_back(p);
    }
  }
  return out;
}

}  // namespace

Status MeshLoadOptions::validate() const {
  if (up_axis != "z" && up_axis != "y") return Status::Error("up_axis expected 'z' or 'y', got '" + up_axis + "'");
  if (!std::isfinite(scale) || scale <= 0.0) return Status::Error("scale expected > 0, got " + std::to_string(scale));
  if (!fit_size.allFinite() || (!fitsToBox() && !fit_size.isZero())) {
    return Status::Error("fit_size expected three sizes > 0 (or all 0: no fit)");
  }
  if (fitsToBox() && scale != 1.0) return Status::Error("scale expected 1 with fit_size (the fit chooses the scale)");
  if (!offset.allFinite()) return Status::Error("offset expected finite");
  if (crop.min.hasNaN() || crop.max.hasNaN()) return Status::Error("crop box has NaN bounds");
  if (crop.empty()) return Status::Error("crop box is empty (min > max on some axis)");
  return Status::Ok();
}

TriangleMesh cropMesh(const TriangleMesh& mesh, const AlignedBox& box) {
  TriangleMesh out;
  out.vertices = mesh.vertices;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    Polygon poly{mesh.vertices[t[0]].cast<double>(), mesh.vertices[t[1]].cast<double>(),
                 mesh.vertices[t[2]].cast<double>()};
    bool inside = true;
    for (const Eigen::Vector3d& p : poly) inside = inside && box.contains(p);
    if (inside) {
      out.triangles.push_back(t);
      continue;
    }
    for (int axis = 0; axis < 3 && poly.size() >= 3; ++axis) {
      if (std::isfinite(box.min[axis])) poly = clipAgainstPlane(poly, axis, box.min[axis], -1.0);
      if (poly.size() >= 3 && std::isfinite(box.max[axis])) poly = clipAgainstPlane(poly, axis, box.max[axis], 1.0);
    }
    if (poly.size() < 3) continue;
    const int base = static_cast<int>(out.vertices.size());
    for (const Eigen::Vector3d& p : poly) out.vertices.push_back(p.cast<float>());
    for (int k = 1; k + 1 < static_cast<int>(poly.size()); ++k) out.triangles.emplace_back(base, base + k, base + k + 1);
  }
  out.removeDegenerate();
  // Drop vertices no triangle uses any more.
  std::vector<int> remap(out.vertices.size(), -1);
  TriangleMesh compact;
  for (Eigen::Vector3i t : out.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (remap[t[k]] < 0) {
        remap[t[k]] = static_cast<int>(compact.vertices.size());
        compact.vertices.push_back(out.vertices[t[k]]);
      }
      t[k] = remap[t[k]];
    }
    compact.triangles.push_back(t);
  }
  return compact;
}

double applyLoadOptions(const MeshLoadOptions& options, TriangleMesh* mesh) {
  if (options.up_axis == "y") {
    for (Eigen::Vector3f& v : mesh->vertices) v = Eigen::Vector3f(v.x(), -v.z(), v.y());
  }
  double scale = options.scale;
  Eigen::Vector3d offset = options.offset;
  if (options.fitsToBox() && !mesh->empty()) {
    const AlignedBox box = mesh->bounds();
    const Eigen::Vector3d extent = box.max - box.min;
    double fit = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
      if (extent[axis] > 0.0) fit = std::min(fit, options.fit_size[axis] / extent[axis]);
    }
    if (std::isfinite(fit)) scale = fit;  // a single point keeps scale 1
    const Eigen::Vector3d anchor(0.5 * (box.min.x() + box.max.x()), 0.5 * (box.min.y() + box.max.y()), box.min.z());
    offset -= scale * anchor;
  }
  mesh->scaleAndOffset(scale, offset);
  if (options.hasCrop()) *mesh = cropMesh(*mesh, options.crop);
  return scale;
}

Status loadMesh(const std::string& path, const MeshLoadOptions& options, TriangleMesh* mesh) {
  if (Status s = options.validate(); !s) return Status::Error("mesh '" + path + "': " + s.message());
  if (path.empty()) return Status::Error("mesh file path is empty");
  if (!fileReadable(path)) return Status::Error("mesh file '" + path + "' does not exist or cannot be read");

  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_JoinIdenticalVertices |
                aiProcess_SortByPType);
  if (scene == nullptr) {
    return Status::Error("mesh file '" + path + "' could not be read: " + importer.GetErrorString());
  }
  TriangleMesh loaded;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* am = scene->mMeshes[m];
    const int base = static_cast<int>(loaded.vertices.size());
    for (unsigned v = 0; v < am->mNumVertices; ++v) {
      const aiVector3D& p = am->mVertices[v];
      loaded.vertices.emplace_back(p.x, p.y, p.z);
    }
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;
      loaded.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                                    base + static_cast<int>(face.mIndices[2]));
    }
  }
  loaded.removeDegenerate();
  if (loaded.empty()) return Status::Error("mesh file '" + path + "' holds no triangles");
  applyLoadOptions(options, &loaded);
  if (loaded.empty()) return Status::Error("mesh file '" + path + "' has no triangle inside the crop box");
  *mesh = std::move(loaded);
  return Status::Ok();
}

Status saveMesh(const TriangleMesh& mesh, const std::string& path) {
  const std::string ext = lowerExtension(path);
  std::string format;
  if (ext == "ply") format = "plyb";
  else if (ext == "stl") format = "stlb";
  else return Status::Error("cannot write '" + path + "': extension expected .ply or .stl");
  if (mesh.empty()) return Status::Error("cannot write '" + path + "': the mesh is empty");
  for (const Eigen::Vector3i& t : mesh.triangles) {
    if ((t.array() < 0).any() || (t.array() >= static_cast<int>(mesh.vertices.size())).any()) {
      return Status::Error("cannot write '" + path + "': a triangle indexes a vertex that does not exist");
    }
  }

  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode();
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh*[1]{new aiMesh()};
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  aiMesh* am = scene->mMeshes[0];
  am->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  am->mMaterialIndex = 0;
  am->mNumVertices = static_cast<unsigned>(mesh.vertices.size());
  am->mVertices = new aiVector3D[am->mNumVertices];
  for (unsigned i = 0; i < am->mNumVertices; ++i) {
    const Eigen::Vector3f& v = mesh.vertices[i];
    am->mVertices[i] = aiVector3D(v.x(), v.y(), v.z());
  }
  am->mNumFaces = static_cast<unsigned>(mesh.triangles.size());
  am->mFaces = new aiFace[am->mNumFaces];
  for (unsigned i = 0; i < am->mNumFaces; ++i) {
    aiFace& face = am->mFaces[i];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int k = 0; k < 3; ++k) face.mIndices[k] = static_cast<unsigned>(mesh.triangles[i][k]);
  }

  const std::string tmp = path + ".tmp";
  Assimp::Exporter exporter;
  if (exporter.Export(scene.get(), format, tmp) != AI_SUCCESS) {
    std::remove(tmp.c_str());
    return Status::Error("cannot write '" + path + "': " + exporter.GetErrorString());
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    return Status::Error("cannot rename '" + tmp + "' to '" + path + "'");
  }
  return Status::Ok();
}

}  // namespace surface_nbv
