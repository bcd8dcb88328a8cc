// The TSDF the reconstruction mesh is extracted from.
//
// With TsdfConfig::mesh_truncation set (and a truncation, weight drop-off
// or voxel size that differs from the planning map's), it is a second TSDF
// fused from the same frames; otherwise it is the planning map itself and
// costs nothing. A TSDF writes negative distances up to the truncation
// behind every surface it sees, so a wall thinner than that is eroded from
// both sides: on the power plant, fusing four recorded flights again with
// 2.5 voxels instead of 3 lowers the RMSE from 5.89 to 5.57 cm and adds 0.24
// points of coverage (2 voxels: 5.24 cm, 0.26 points less). Finer voxels
// than the planning map's follow convex edges more closely (0.1 m on the
// power plant: 89.53 -> 92.19 % on ten flights, session 12). Planning keeps
// the map whose known/unknown split the explorer was measured with, because
// flying on the shorter truncation explored worse
// (docs/planner_experiments.md, session 7).
//
// Feed it every frame the planning map gets, with the same weight scale.
#pragma once

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "surface_nbv/map/tsdf_integrator.h"
#include "surface_nbv/map/tsdf_map.h"

namespace surface_nbv {

class MeshLayer {
 public:
  // planning: the map every frame is also integrated into (not owned; must
  // outlive this object). Its config decides whether a separate layer exists.
  explicit MeshLayer(const TsdfMap* planning);
  ~MeshLayer();  // waits for the frames in flight (integrateDepthBehind)
  MeshLayer(const MeshLayer&) = delete;
  MeshLayer& operator=(const MeshLayer&) = delete;

  // True when this layer is a TSDF of its own (mesh_truncation in effect).
  bool separate() const { return map_ != nullptr; }
  // The map to mesh: the separate layer, or the planning map.
  const TsdfMap& map() const { return map_ ? *map_ : *planning_; }

  // As TsdfIntegrator's; Ok without doing anything unless separate().
  Status integrateDepth(const DepthCamera& camera, const DepthImage& depth, const Transform& T_W_C);
  Status integratePoints(const std::vector<Eigen::Vector3f>& points_S, const Transform& T_W_S, double max_range);
  // One frame into the planning map (through `planning`, its integrator) and
  // into this layer. With threads >= 2 and a separate layer, the two maps are
  // fused side by side on one thread each rather than one after the other on
  // `threads` each: splitting one map's blocks over two threads gains little
  // (power plant, seed 1: integration 24.2 s on one thread, 35.4 s on two).
  // Both maps end exactly as fused one after the other. Returns the planning
  // map's status; the layer's goes to *layer, or, when layer is null, is
  // returned if the planning map's was Ok.
  Status integrateDepthWith(TsdfIntegrator* planning, const DepthCamera& camera, const DepthImage& depth,
                            const Transform& T_W_C, int threads, IntegrationStats* stats = nullptr,
                            Status* layer = nullptr);
  // The same frame as integrateDepthWith(), but the layer's fusion runs on a
  // thread of its own while the caller goes on: the planning map is fused
  // on the calling thread (threads - 1 of them) once fewer than
  // queueDepth() frames wait for the layer; then this frame joins them, as
  // copies of `camera` and `depth`. The layer takes the same frames in the
  // same order, so it ends voxel for voxel as integrateDepthWith() leaves
  // it. A failure of the layer on an earlier frame goes to *layer when
  // given (the planning map's status is returned), else it is returned
  // unless the planning map failed. Call finish() before map() is read:
  // every other method and the destructor call it first, and report a
  // failure it returns as the layer's (after doing their own work).
  Status integrateDepthBehind(TsdfIntegrator* planning, const DepthCamera& camera, const DepthImage& depth,
                              const Transform& T_W_C, int threads, IntegrationStats* stats = nullptr,
                              Status* layer = nullptr);
  // How many frames integrateDepthBehind() may leave to the layer before it
  // waits (at least 1, the default: the previous frame only). A deeper
  // queue lets the layer catch up while the caller does work of its own on
  // one thread (nbv_mission plans its legs), at one depth image of memory
  // per frame; the maps end the same either way.
  void setQueueDepth(size_t frames);
  size_t queueDepth() const { return queue_depth_; }
  // Waits for the layer's frames in flight; the first failure among them
  // since the last report (Ok when none).
  Status finish();
  // Whether queueDepth() frames are in flight (a real-time caller may fuse
  // the next frame into the planning map alone instead of waiting).
  bool busy() const;
  // Frames waiting for the layer or being fused into it.
  size_t pending() const;
  Status markFree(const Eigen::Vector3d& center, double radius);
  void setWeightScale(double scale);
  // After the planning map was loaded from `path`: the layer starts again
  // from the same file, so the mesh shows what was loaded. A layer of finer
  // voxels (TsdfConfig::mesh_voxel_size) gets the file resampled: weights
  // of the voxel around each centre, distances interpolated.
  Status reload(const std::string& path);

 private:
  const TsdfMap* planning_;
  std::unique_ptr<TsdfMap> map_;
  std::unique_ptr<TsdfIntegrator> integrator_;
  size_t queue_depth_ = 1;  // the caller's setting; the layer's thread never reads it

  // The layer's thread and the frames it has still to fuse (the front one
  // is in progress); every member below is guarded by mutex_.
  struct Frame {
    DepthCamera camera;
    DepthImage depth;
    Transform T_W_C;
  };
  void work();
  mutable std::mutex mutex_;
  std::condition_variable queued_, fused_;
  std::deque<Frame> frames_;
  std::vector<DepthImage> spare_;  // buffers of fused frames, for the next ones
  Status failure_;                 // the first failure not reported yet
  bool stop_ = false;
  std::thread worker_;  // started with the first frame behind
};

}  // namespace surface_nbv
