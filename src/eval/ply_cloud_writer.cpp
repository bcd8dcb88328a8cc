#include "surface_nbv/eval/ply_cloud_writer.h"

#include <cstdio>
#include <cstring>
#include <fstream>

namespace surface_nbv {
namespace {

void putFloat(float v, std::string* out) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof(bits));
  for (int k = 0; k < 4; ++k) out->push_back(static_cast<char>((bits >> (8 * k)) & 0xffu));
}

}  // namespace

Status writePlyCloud(const std::string& path, const PlyCloud& cloud) {
  const size_t n = cloud.points.size();
  const bool normals = !cloud.normals.empty(), scalars = !cloud.scalars.empty();
  if ((normals && cloud.normals.size() != n) || cloud.colors.size() != n || (scalars && cloud.scalars.size() != n)) {
    return Status::Error("PLY cloud '" + path + "': normals, colours and scalars expected one per point");
  }
  if (scalars && cloud.scalar_name.empty()) return Status::Error("PLY cloud '" + path + "': scalar_name expected");
  std::string header = "ply\nformat binary_little_endian 1.0\ncomment surface_nbv evaluation\nelement vertex " +
                       std::to_string(n) + "\nproperty float x\nproperty float y\nproperty float z\n";
  if (normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
  header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (scalars) header += "property float " + cloud.scalar_name + "\n";
  header += "end_header\n";
  std::string body;
  body.reserve(n * (15 + (normals ? 12 : 0) + (scalars ? 4 : 0)));
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) putFloat(cloud.points[i][k], &body);
    if (normals) {
      for (int k = 0; k < 3; ++k) putFloat(cloud.normals[i][k], &body);
    }
    for (int k = 0; k < 3; ++k) body.push_back(static_cast<char>(cloud.colors[i][k]));
    if (scalars) putFloat(cloud.scalars[i], &body);
  }
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.write(body.data(), static_cast<std::streamsize>(body.size()));
    if (!out) {
      std::remove(tmp.c_str());
      return Status::Error("cannot write PLY cloud '" + path + "'");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    return Status::Error("cannot rename '" + tmp + "' to '" + path + "'");
  }
  return Status::Ok();
}

}  // namespace surface_nbv
