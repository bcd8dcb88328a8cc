#include "surface_nbv/map/mesh_layer.h"

#include <algorithm>
#include <exception>
#include <string>

#include "surface_nbv/map/map_io.h"
#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {

MeshLayer::MeshLayer(const TsdfMap* planning) : planning_(planning) {
  const TsdfConfig& c = planning->config();
  if (!c.hasMeshLayer()) return;
  map_ = std::make_unique<TsdfMap>(c.meshLayerConfig());
  integrator_ = std::make_unique<TsdfIntegrator>(map_.get());
}

MeshLayer::~MeshLayer() {
  finish();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  queued_.notify_all();
  if (worker_.joinable()) worker_.join();
}

Status MeshLayer::finish() {
  std::unique_lock<std::mutex> lock(mutex_);
  fused_.wait(lock, [this] { return frames_.empty(); });
  Status failure = failure_;
  failure_ = Status::Ok();
  return failure;
}

void MeshLayer::setQueueDepth(size_t frames) { queue_depth_ = std::max<size_t>(1, frames); }

bool MeshLayer::busy() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return frames_.size() >= queue_depth_;
}

size_t MeshLayer::pending() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return frames_.size();
}

void MeshLayer::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    queued_.wait(lock, [this] { return stop_ || !frames_.empty(); });
    if (frames_.empty()) return;
    // References to a deque's elements survive push_back; only this thread pops.
    Frame& frame = frames_.front();
    lock.unlock();
    const int layer_threads = integrator_->threads();
    integrator_->setThreads(1);
    Status s;
    try {  // an exception would end the process here: it becomes the layer's failure
      s = integrator_->integrateDepth(frame.camera, frame.depth, frame.T_W_C);
    } catch (const std::exception& e) {
      s = Status::Error(std::string("mesh layer fusion: ") + e.what());
    }
    integrator_->setThreads(layer_threads);
    lock.lock();
    if (!s && failure_.ok()) failure_ = s;
    spare_.push_back(std::move(frame.depth));
    frames_.pop_front();
    fused_.notify_all();
  }
}

Status MeshLayer::integrateDepth(const DepthCamera& camera, const DepthImage& depth, const Transform& T_W_C) {
  const Status previous = finish();
  const Status s = integrator_ ? integrator_->integrateDepth(camera, depth, T_W_C) : Status::Ok();
  return previous ? s : previous;
}

Status MeshLayer::integrateDepthBehind(TsdfIntegrator* planning, const DepthCamera& camera, const DepthImage& depth,
                                       const Transform& T_W_C, int threads, IntegrationStats* stats, Status* layer) {
  Status layered;
  Status planned;
  if (!integrator_ || threads < 2) {
    layered = finish();
    Status now;
    planned = integrateDepthWith(planning, camera, depth, T_W_C, threads, stats, &now);
    if (layered) layered = now;
  } else {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      fused_.wait(lock, [this] { return frames_.size() < queue_depth_; });
      layered = failure_;
      failure_ = Status::Ok();
    }
    const int planning_threads = planning->threads();
    planning->setThreads(threads - 1);
    planned = planning->integrateDepth(camera, depth, T_W_C, stats);
    planning->setThreads(planning_threads);
    if (planned) {
      DepthImage copy;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!spare_.empty()) {
          copy = std::move(spare_.back());
          spare_.pop_back();
        }
      }
      copy = depth;  // outside the lock, which the layer's thread takes at every frame's end
      {
        std::lock_guard<std::mutex> lock(mutex_);
        frames_.push_back(Frame{camera, std::move(copy), T_W_C});
      }
      if (!worker_.joinable()) worker_ = std::thread(&MeshLayer::work, this);
      queued_.notify_one();
    }
  }
  if (layer != nullptr) {
    *layer = layered;
    return planned;
  }
  return planned ? layered : planned;
}

Status MeshLayer::integrateDepthWith(TsdfIntegrator* planning, const DepthCamera& camera, const DepthImage& depth,
                                     const Transform& T_W_C, int threads, IntegrationStats* stats, Status* layer) {
  const Status previous = finish();  // a failure of the layer behind, reported as the layer's
  Status planned, layered;
  if (!integrator_ || threads < 2) {
    planned = planning->integrateDepth(camera, depth, T_W_C, stats);
    layered = planned ? integrateDepth(camera, depth, T_W_C) : Status::Ok();
  } else {
    // One thread each for this frame, then the counts the callers had.
    const int planning_threads = planning->threads(), layer_threads = integrator_->threads();
    planning->setThreads(1);
    integrator_->setThreads(1);
    parallelFor(2, 2, [&](size_t i) {
      if (i == 0) {
        planned = planning->integrateDepth(camera, depth, T_W_C, stats);
      } else {
        layered = integrator_->integrateDepth(camera, depth, T_W_C);
      }
    });
    planning->setThreads(planning_threads);
    integrator_->setThreads(layer_threads);
  }
  if (!previous) layered = previous;
  if (layer != nullptr) {
    *layer = layered;
    return planned;
  }
  return planned ? layered : planned;
}

Status MeshLayer::integratePoints(const std::vector<Eigen::Vector3f>& points_S, const Transform& T_W_S,
                                  double max_range) {
  const Status previous = finish();
  const Status s = integrator_ ? integrator_->integratePoints(points_S, T_W_S, max_range) : Status::Ok();
  return previous ? s : previous;
}

Status MeshLayer::markFree(const Eigen::Vector3d& center, double radius) {
  const Status previous = finish();
  const Status s = integrator_ ? integrator_->markFree(center, radius) : Status::Ok();
  return previous ? s : previous;
}

void MeshLayer::setWeightScale(double scale) {
  finish();  // a failed fusion in flight was already the caller's to see
  if (integrator_) integrator_->setWeightScale(scale);
}

namespace {

// Fills `fine` from `coarse` (a map of larger voxels over the same bounds):
// each fine voxel inside an allocated coarse block takes the weight of the
// coarse voxel holding its centre, and the distance interpolated trilinearly
// between the eight coarse centres around it when all eight were seen (that
// voxel's own otherwise), clamped to the fine map's truncation.
void resample(const TsdfMap& coarse, TsdfMap* fine) {
  const double ratio = coarse.voxelSize() / fine->voxelSize();
  const float trunc = static_cast<float>(fine->config().truncationDistance());
  const Eigen::Vector3d origin = coarse.config().bounds.min;
  for (const auto& block : coarse.blocks()) {
    const Eigen::Array3d lo = (block->index.array() * kBlockSize).cast<double>() * ratio;
    const Eigen::Array3d hi = ((block->index.array() + 1) * kBlockSize).cast<double>() * ratio;
    const Eigen::Vector3i first = lo.floor().cast<int>(), last = hi.ceil().cast<int>();
    for (int z = first.z(); z < last.z(); ++z)
      for (int y = first.y(); y < last.y(); ++y)
        for (int x = first.x(); x < last.x(); ++x) {
          const Eigen::Vector3i f(x, y, z);
          if (!fine->voxelInBounds(f)) continue;
          const Eigen::Vector3d p = fine->voxelCenter(f);
          Eigen::Vector3i c;
          if (!coarse.voxelIndex(p, &c) || TsdfMap::blockOfVoxel(c) != block->index) continue;
          const TsdfVoxel* own = coarse.voxel(c);
          if (own == nullptr || own->w <= 0.0f) continue;
          // Trilinear weights from the coarse centres below p on each axis.
          const Eigen::Vector3d g = (p - origin) / coarse.voxelSize() - Eigen::Vector3d::Constant(0.5);
          const Eigen::Vector3i base = g.array().floor().cast<int>();
          const Eigen::Vector3d t = g - base.cast<double>();
          double phi = 0.0;
          bool all = true;
          for (int k = 0; k < 8; ++k) {
            const Eigen::Vector3i o(k & 1, (k >> 1) & 1, (k >> 2) & 1);
            const TsdfVoxel* v = coarse.voxel(base + o);
            if (v == nullptr || v->w <= 0.0f) {
              all = false;
              break;
            }
            const Eigen::Vector3d share = (o.cast<double>().array() * t.array() +
                                           (1 - o.cast<double>().array()) * (1.0 - t.array()));
            phi += share.prod() * v->phi;
          }
          TsdfVoxel* out = fine->allocateVoxel(f);
          if (out == nullptr) continue;  // the block cap: counted by the map
          out->phi = std::clamp(all ? static_cast<float>(phi) : own->phi, -trunc, trunc);
          out->w = own->w;
        }
  }
}

}  // namespace

Status MeshLayer::reload(const std::string& path) {
  finish();  // the layer starts again whatever became of the frame in flight
  if (!map_) return Status::Ok();
  auto fresh = std::make_unique<TsdfMap>(map_->config());
  if (fresh->voxelSize() == planning_->voxelSize()) {
    if (Status s = loadMap(path, fresh.get()); !s) return s;
  } else {
    // A layer of other voxels cannot read the planning map's file: it is
    // read at the planning map's voxels and resampled.
    TsdfMap loaded(planning_->config()), staged(map_->config());
    if (Status s = loadMap(path, &loaded); !s) return s;
    resample(loaded, &staged);
    fresh->adoptBlocks(&staged);  // stamps every block as changed, as loadMap does
  }
  map_ = std::move(fresh);
  integrator_ = std::make_unique<TsdfIntegrator>(map_.get());
  return Status::Ok();
}

}  // namespace surface_nbv
