#include "surface_nbv/util/png_writer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <zlib.h>

namespace surface_nbv {
namespace {

void putU32(std::vector<uint8_t>* out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out->push_back(static_cast<uint8_t>(v >> shift));
}

void putChunk(std::vector<uint8_t>* out, const char* type, const std::vector<uint8_t>& data) {
  putU32(out, static_cast<uint32_t>(data.size()));
  const size_t start = out->size();
  out->insert(out->end(), type, type + 4);
  out->insert(out->end(), data.begin(), data.end());
  const uLong crc = crc32(0L, out->data() + start, static_cast<uInt>(out->size() - start));
  putU32(out, static_cast<uint32_t>(crc));
}

}  // namespace

Status writePng(const std::string& path, int width, int height, int channels, const std::vector<uint8_t>& pixels) {
  if (width <= 0 || height <= 0) return Status::Error("png '" + path + "': size must be positive");
  if (channels != 1 && channels != 3) return Status::Error("png '" + path + "': channels expected 1 or 3");
  const size_t row_bytes = static_cast<size_t>(width) * channels;
  if (pixels.size() != row_bytes * height) return Status::Error("png '" + path + "': pixel buffer has the wrong size");

  std::vector<uint8_t> raw;
  raw.reserve((row_bytes + 1) * height);
  for (int r = 0; r < height; ++r) {
    raw.push_back(0);  // filter type: none
    raw.insert(raw.end(), pixels.begin() + r * row_bytes, pixels.begin() + (r + 1) * row_bytes);
  }
  uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
  std::vector<uint8_t> packed(packed_size);
  if (compress2(packed.data(), &packed_size, raw.data(), static_cast<uLong>(raw.size()), 6) != Z_OK) {
    return Status::Error("png '" + path + "': zlib compression failed");
  }
  packed.resize(packed_size);

  std::vector<uint8_t> file = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<uint8_t> header;
  putU32(&header, static_cast<uint32_t>(width));
  putU32(&header, static_cast<uint32_t>(height));
  header.push_back(8);                          // bit depth
  header.push_back(channels == 1 ? 0 : 2);      // colour type: grey or RGB
  header.insert(header.end(), {0, 0, 0});       // compression, filter, interlace
  putChunk(&file, "IHDR", header);
  putChunk(&file, "IDAT", packed);
  putChunk(&file, "IEND", {});

  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out.write(reinterpret_cast<const char*>(file.data()), static_cast<std::streamsize>(file.size()));
    if (!out) return Status::Error("png '" + path + "': cannot write");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) return Status::Error("png '" + path + "': cannot rename");
  return Status::Ok();
}

std::vector<uint8_t> colorizeDepth(const std::vector<float>& depth, float lo, float hi) {
  // A few control points of a viridis-like ramp, reversed so near is bright.
  static const std::array<std::array<float, 3>, 5> ramp = {{
      {253, 231, 37}, {94, 201, 98}, {33, 145, 140}, {59, 82, 139}, {68, 1, 84}}};
  std::vector<uint8_t> rgb(depth.size() * 3, 0);
  const float span = hi > lo ? hi - lo : 1.0f;
  for (size_t i = 0; i < depth.size(); ++i) {
    if (!std::isfinite(depth[i])) continue;
    const float x = std::clamp((depth[i] - lo) / span, 0.0f, 1.0f) * (ramp.size() - 1);
    const size_t k = std::min(static_cast<size_t>(x), ramp.size() - 2);
    const float f = x - k;
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = static_cast<uint8_t>(ramp[k][c] + f * (ramp[k + 1][c] - ramp[k][c]));
  }
  return rgb;
}

}  // namespace surface_nbv
