#include "surface_nbv/map/map_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <tuple>
#include <vector>

namespace surface_nbv {
namespace {

constexpr char kMagic[8] = {'S', 'N', 'B', 'V', 'T', 'S', 'D', 'F'};
constexpr size_t kHeaderBytes = 8 + 4 + 8 + 4 + 4 + 8 + 24 + 24 + 8;
constexpr size_t kBlockBytes = 3 * 4 + kBlockVoxels * 2 * 4;
constexpr size_t kCrcBytes = 4;
constexpr size_t kFlushBytes = 1 << 20;

uint32_t crcOf(const uint8_t* data, size_t size, uint32_t crc = 0) {
  uLong c = crc;
  while (size > 0) {
    const size_t chunk = std::min<size_t>(size, 1u << 30);
    c = crc32(c, data, static_cast<uInt>(chunk));
    data += chunk;
    size -= chunk;
  }
  return static_cast<uint32_t>(c);
}

std::string errnoText() { return std::strerror(errno); }

// Every write goes through a buffer that is checksummed as it is flushed.
class Writer {
 public:
  explicit Writer(int fd) : fd_(fd) { buf_.reserve(kFlushBytes + kBlockBytes); }

  void u32(uint32_t v) {
    for (int i = 0; i < 4; ++i) buf_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void u64(uint64_t v) {
    for (int i = 0; i < 8; ++i) buf_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void f32(float v) {
    uint32_t u;
    std::memcpy(&u, &v, sizeof(u));
    u32(u);
  }
  void f64(double v) {
    uint64_t u;
    std::memcpy(&u, &v, sizeof(u));
    u64(u);
  }
  void raw(const char* data, size_t size) { buf_.insert(buf_.end(), data, data + size); }

  // Writes the buffer once it is large (or always when `force`).
  bool flush(bool force) {
    if (buf_.empty() || (!force && buf_.size() < kFlushBytes)) return true;
    crc_ = crcOf(buf_.data(), buf_.size(), crc_);
    const uint8_t* p = buf_.data();
    size_t left = buf_.size();
    while (left > 0) {
      const ssize_t n = ::write(fd_, p, left);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      p += n;
      left -= static_cast<size_t>(n);
    }
    buf_.clear();
    return true;
  }
  uint32_t crc() const { return crc_; }

 private:
  int fd_;
  std::vector<uint8_t> buf_;
  uint32_t crc_ = 0;
};

// Bounds-checked little-endian reads; the caller has checked the size.
class Reader {
 public:
  explicit Reader(const std::vector<uint8_t>& data) : data_(data) {}
  uint32_t u32() {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<uint32_t>(data_[pos_++]) << (8 * i);
    return v;
  }
  uint64_t u64() {
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<uint64_t>(data_[pos_++]) << (8 * i);
    return v;
  }
  int32_t i32() { return static_cast<int32_t>(u32()); }
  float f32() {
    const uint32_t u = u32();
    float v;
    std::memcpy(&v, &u, sizeof(v));
    return v;
  }
  double f64() {
    const uint64_t u = u64();
    double v;
    std::memcpy(&v, &u, sizeof(v));
    return v;
  }
  void skip(size_t n) { pos_ += n; }

 private:
  const std::vector<uint8_t>& data_;
  size_t pos_ = 0;
};

std::string directoryOf(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

Status writeMapFile(const TsdfMap& map, int fd, const std::string& tmp) {
  std::vector<const TsdfBlock*> blocks;
  blocks.reserve(map.numBlocks());
  for (const auto& b : map.blocks()) blocks.push_back(b.get());
  std::sort(blocks.begin(), blocks.end(), [](const TsdfBlock* a, const TsdfBlock* b) {
    return std::make_tuple(a->index.z(), a->index.y(), a->index.x()) <
           std::make_tuple(b->index.z(), b->index.y(), b->index.x());
  });
  const TsdfConfig& c = map.config();
  Writer out(fd);
  out.raw(kMagic, sizeof(kMagic));
  out.u32(kMapFormatVersion);
  out.f64(c.voxel_size);
  out.u32(static_cast<uint32_t>(kBlockSize));
  out.f32(c.w_th);
  out.f64(c.truncationDistance());
  for (int i = 0; i < 3; ++i) out.f64(c.bounds.min[i]);
  for (int i = 0; i < 3; ++i) out.f64(c.bounds.max[i]);
  out.u64(blocks.size());
  const auto fail = [&tmp]() { return Status::Error("cannot write map file '" + tmp + "': " + errnoText()); };
  for (const TsdfBlock* b : blocks) {
    for (int i = 0; i < 3; ++i) out.u32(static_cast<uint32_t>(b->index[i]));
    for (const TsdfVoxel& v : b->voxels) {
      out.f32(v.phi);
      out.f32(v.w);
    }
    if (!out.flush(false)) return fail();
  }
  if (!out.flush(true)) return fail();
  const uint32_t crc = out.crc();
  out.u32(crc);
  if (!out.flush(true)) return fail();
  if (::fsync(fd) != 0) return Status::Error("cannot fsync map file '" + tmp + "': " + errnoText());
  return Status::Ok();
}

Status readWholeFile(const std::string& path, std::vector<uint8_t>* data) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return Status::Error("cannot open map file '" + path + "': " + errnoText());
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return Status::Error("map file '" + path + "' is not a regular file");
  }
  data->resize(static_cast<size_t>(st.st_size));
  size_t got = 0;
  while (got < data->size()) {
    const ssize_t n = ::read(fd, data->data() + got, data->size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string why = errnoText();
      ::close(fd);
      return Status::Error("cannot read map file '" + path + "': " + why);
    }
    if (n == 0) break;
    got += static_cast<size_t>(n);
  }
  ::close(fd);
  data->resize(got);
  return Status::Ok();
}

}  // namespace

Status saveMap(const TsdfMap& map, const std::string& path) {
  if (path.empty()) return Status::Error("map file path is empty");
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return Status::Error("cannot create map file '" + tmp + "': " + errnoText());
  Status written = writeMapFile(map, fd, tmp);
  if (::close(fd) != 0 && written) written = Status::Error("cannot close map file '" + tmp + "': " + errnoText());
  if (!written) {
    ::unlink(tmp.c_str());
    return written;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = errnoText();
    ::unlink(tmp.c_str());
    return Status::Error("cannot rename '" + tmp + "' to '" + path + "': " + why);
  }
  const int dir = ::open(directoryOf(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
  return Status::Ok();
}

Status loadMap(const std::string& path, TsdfMap* map) {
  std::vector<uint8_t> data;
  if (Status s = readWholeFile(path, &data); !s) return s;
  const auto bad = [&path](const std::string& what) { return Status::Error("map file '" + path + "': " + what); };
  const size_t size = data.size();
  if (size < sizeof(kMagic) || std::memcmp(data.data(), kMagic, sizeof(kMagic)) != 0) {
    return bad("not a surface_nbv TSDF map (no \"SNBVTSDF\" magic at the start of its " + std::to_string(size) +
               " bytes)");
  }
  if (size < sizeof(kMagic) + 4) return bad("truncated inside the header (" + std::to_string(size) + " bytes)");
  Reader in(data);
  in.skip(sizeof(kMagic));
  const uint32_t version = in.u32();
  if (version != kMapFormatVersion) {
    return bad("format version " + std::to_string(version) + ", this build reads version " +
               std::to_string(kMapFormatVersion));
  }
  if (size < kHeaderBytes + kCrcBytes) {
    return bad("truncated: " + std::to_string(size) + " bytes, the header and checksum alone take " +
               std::to_string(kHeaderBytes + kCrcBytes));
  }
  const double voxel_size = in.f64();
  const uint32_t block_size = in.u32();
  in.f32();
  in.f64();
  Eigen::Vector3d bounds_min, bounds_max;
  for (int i = 0; i < 3; ++i) bounds_min[i] = in.f64();
  for (int i = 0; i < 3; ++i) bounds_max[i] = in.f64();
  const uint64_t num_blocks = in.u64();
  const size_t room = (size - kHeaderBytes - kCrcBytes) / kBlockBytes;
  if (num_blocks > room) {
    return bad("truncated: it declares " + std::to_string(num_blocks) + " blocks but " + std::to_string(size) +
               " bytes hold at most " + std::to_string(room));
  }
  const size_t expected = kHeaderBytes + static_cast<size_t>(num_blocks) * kBlockBytes + kCrcBytes;
  if (size != expected) {
    return bad("size mismatch: " + std::to_string(num_blocks) + " blocks need " + std::to_string(expected) +
               " bytes, the file has " + std::to_string(size) + " (truncated or trailing data)");
  }
  uint32_t stored_crc = 0;
  for (int i = 0; i < 4; ++i) stored_crc |= static_cast<uint32_t>(data[size - kCrcBytes + i]) << (8 * i);
  if (crcOf(data.data(), size - kCrcBytes) != stored_crc) return bad("checksum mismatch (the file is corrupted)");

  const TsdfConfig& config = map->config();
  if (block_size != static_cast<uint32_t>(kBlockSize)) {
    return bad("block size " + std::to_string(block_size) + ", this build uses " + std::to_string(kBlockSize));
  }
  if (!(std::abs(voxel_size - config.voxel_size) <= 1e-9 * config.voxel_size)) {
    return bad("voxel size " + std::to_string(voxel_size) + " m differs from the map's " +
               std::to_string(config.voxel_size) + " m");
  }
  if (!((bounds_min - config.bounds.min).cwiseAbs().array() <= 1e-6 * config.voxel_size).all()) {
    return bad("bounds min (" + std::to_string(bounds_min.x()) + ", " + std::to_string(bounds_min.y()) + ", " +
               std::to_string(bounds_min.z()) + ") differs from the map's (" + std::to_string(config.bounds.min.x()) +
               ", " + std::to_string(config.bounds.min.y()) + ", " + std::to_string(config.bounds.min.z()) + ")");
  }
  if (num_blocks > config.max_blocks) {
    return bad(std::to_string(num_blocks) + " blocks exceed the map's max_blocks " +
               std::to_string(config.max_blocks));
  }

  TsdfMap loaded(config);
  for (uint64_t n = 0; n < num_blocks; ++n) {
    Eigen::Vector3i index;
    for (int i = 0; i < 3; ++i) index[i] = in.i32();
    const std::string name = "block (" + std::to_string(index.x()) + ", " + std::to_string(index.y()) + ", " +
                             std::to_string(index.z()) + ")";
    if (!loaded.blockInBounds(index)) return bad(name + " lies outside the map's bounds");
    if (loaded.block(index) != nullptr) return bad(name + " appears twice");
    TsdfBlock* block = loaded.allocateBlock(index);
    if (block == nullptr) return bad("cannot allocate " + name);
    for (TsdfVoxel& v : block->voxels) {
      v.phi = in.f32();
      v.w = in.f32();
      if (!std::isfinite(v.phi) || !std::isfinite(v.w) || v.w < 0.0f) {
        return bad(name + " holds a non-finite value or a negative weight");
      }
    }
  }
  if (!map->adoptBlocks(&loaded)) return bad("internal error: the block grids differ");
  return Status::Ok();
}

}  // namespace surface_nbv
