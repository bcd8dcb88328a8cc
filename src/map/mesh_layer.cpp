#include "surface_nbv/map/mesh_layer.h"

#include "surface_nbv/map/map_io.h"
#include "surface_nbv/util/parallel_for.h"

namespace surface_nbv {

MeshLayer::MeshLayer(const TsdfMap* planning) : planning_(planning) {
  const TsdfConfig& c = planning->config();
  if (!c.hasMeshLayer()) return;
  map_ = std::make_unique<TsdfMap>(c.meshLayerConfig());
  integrator_ = std::make_unique<TsdfIntegrator>(map_.get());
}

Status MeshLayer::integrateDepth(const DepthCamera& camera, const DepthImage& depth, const Transform& T_W_C) {
  return integrator_ ? integrator_->integrateDepth(camera, depth, T_W_C) : Status::Ok();
}

Status MeshLayer::integrateDepthWith(TsdfIntegrator* planning, const DepthCamera& camera, const DepthImage& depth,
                                     const Transform& T_W_C, int threads, IntegrationStats* stats, Status* layer) {
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
  if (layer != nullptr) {
    *layer = layered;
    return planned;
  }
  return planned ? layered : planned;
}

Status MeshLayer::integratePoints(const std::vector<Eigen::Vector3f>& points_S, const Transform& T_W_S,
                                  double max_range) {
  return integrator_ ? integrator_->integratePoints(points_S, T_W_S, max_range) : Status::Ok();
}

Status MeshLayer::markFree(const Eigen::Vector3d& center, double radius) {
  return integrator_ ? integrator_->markFree(center, radius) : Status::Ok();
}

void MeshLayer::setWeightScale(double scale) {
  if (integrator_) integrator_->setWeightScale(scale);
}

Status MeshLayer::reload(const std::string& path) {
  if (!map_) return Status::Ok();
  auto fresh = std::make_unique<TsdfMap>(map_->config());
  if (Status s = loadMap(path, fresh.get()); !s) return s;
  map_ = std::move(fresh);
  integrator_ = std::make_unique<TsdfIntegrator>(map_.get());
  return Status::Ok();
}

}  // namespace surface_nbv
