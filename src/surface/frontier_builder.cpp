#include "surface_nbv/surface/frontier_builder.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <cmath>
#include <unordered_map>

#include "surface_nbv/surface/chunked_for.h"

namespace surface_nbv {
namespace {


using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// An approach viewpoint cannot see its ISE yet (unknown space in between)
// but is there to see it: C_q holds its approach sources too.
void addApproachSources(const std::vector<Ise>& ises, std::vector<Viewpoint>* viewpoints) {
  for (Viewpoint& q : *viewpoints) {
    std::vector<uint32_t> extra;
    for (uint32_t i : q.sources)
      if (ises[i].approach) extra.push_back(i);
    if (extra.empty()) continue;
    std::vector<uint32_t> merged;
    merged.reserve(q.visible.size() + extra.size());
    std::set_union(q.visible.begin(), q.visible.end(), extra.begin(), extra.end(), std::back_inserter(merged));
    q.visible = std::move(merged);
  }
}

}  // namespace

double unknownFraction(const VoxelRayCaster& rays, const Viewpoint& viewpoint, const CameraConfig& camera) {
  constexpr int kColumns = 9, kRows = 6;
  const VoxelStateGrid& grid = rays.grid();
  const Transform T_W_C = viewpoint.cameraPose(camera);
  const double tx = std::tan(0.5 * camera.hfov_deg * M_PI / 180.0), ty = std::tan(0.5 * camera.vfov_deg * M_PI / 180.0);
  const Eigen::Vector3i last = grid.gridVoxels() - Eigen::Vector3i::Ones();
  uint64_t entered = 0, unknown = 0, steps = 0;
  for (int r = 0; r < kRows; ++r)
    for (int c = 0; c < kColumns; ++c) {
      const Eigen::Vector3d d_C(tx * (2.0 * (c + 0.5) / kColumns - 1.0), ty * (2.0 * (r + 0.5) / kRows - 1.0), 1.0);
      const Eigen::Vector3d end = T_W_C * (camera.max_range * d_C);
      Eigen::Vector3i target = ((end - grid.origin()) / grid.voxelSize()).array().floor().cast<int>();
      target = target.cwiseMax(Eigen::Vector3i::Zero()).cwiseMin(last);
      rays.walk(viewpoint.position, target, &steps, [&](size_t i) {
        const uint8_t state = grid.data()[i];
        if (state & VoxelStateGrid::kOccupied) return false;
        ++entered;
        unknown += (state & VoxelStateGrid::kUnknown) ? 1 : 0;
        return true;
      });
    }
  return entered > 0 ? static_cast<double>(unknown) / static_cast<double>(entered) : 1.0;
}

FrontierBuilder::ViewKey FrontierBuilder::keyOf(const Viewpoint& q) {
  const double v[4] = {q.position.x(), q.position.y(), q.position.z(), q.yaw};
  return ViewKey(v);
}

std::vector<uint8_t> FrontierBuilder::nearChanges(double reach, double voxel_size) const {
  // A changed voxel u and a point v with |u - v|_inf <= reach lie in blocks
  // whose indices differ by at most floor(reach / block) + 1 along each axis.
  const VoxelStateGrid& grid = extractor_.states();
  const int k = static_cast<int>(std::floor(reach / (kBlockSize * voxel_size))) + 1;
  const Eigen::Vector3i& g = grid.gridBlocks();
  std::vector<uint8_t> near(grid.numBlockSlots(), 0);
  for (const Eigen::Vector3i& b : extractor_.changedStateBlocks()) near[grid.blockSlot(b)] = 1;
  if (extractor_.changedStateBlocks().empty()) return near;
  // Dilate by k blocks along x, then y, then z (a cube of side 2k + 1).
  std::vector<uint8_t> line;
  for (int axis = 0; axis < 3; ++axis) {
    const int n = g[axis];
    line.resize(static_cast<size_t>(n));
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    Eigen::Vector3i b;
    for (b[a1] = 0; b[a1] < g[a1]; ++b[a1]) {
      for (b[a2] = 0; b[a2] < g[a2]; ++b[a2]) {
        int last = -1 - k;  // the last changed index along the line
        for (b[axis] = 0; b[axis] < n; ++b[axis]) {
          if (near[grid.blockSlot(b)]) last = b[axis];
          line[static_cast<size_t>(b[axis])] = b[axis] - last <= k ? 1 : 0;
        }
        last = n + k;
        for (b[axis] = n - 1; b[axis] >= 0; --b[axis]) {
          if (near[grid.blockSlot(b)]) last = b[axis];
          if (last - b[axis] <= k) line[static_cast<size_t>(b[axis])] = 1;
        }
        for (b[axis] = 0; b[axis] < n; ++b[axis]) near[grid.blockSlot(b)] = line[static_cast<size_t>(b[axis])];
      }
    }
  }
  return near;
}

void FrontierBuilder::searchPoses(const TsdfMap& map, const CollisionMap& collision, bool keep,
                                  const VoxelRayCaster& rays, const VoxelRayCaster* approach,
                                  std::vector<Viewpoint>* poses, std::vector<PoseSearch>* searches, Frontier* out) {
  const VoxelStateGrid& grid = extractor_.states();
  const std::vector<Eigen::Vector3i> voxels = extractor_.ises();
  const AlignedBox& bounds = map.config().bounds;
  out->ises.resize(voxels.size());
  poses->assign(voxels.size(), Viewpoint());
  searches->assign(voxels.size(), PoseSearch());
  // A changed voxel can change an ISE's search within maxDistance() (the
  // candidates) plus the cells distance() reads at a candidate (capCells() + 1
  // around it, each changed only within the cap of a changed cell).
  std::vector<uint8_t> near;
  if (keep) {
    near = nearChanges(generator_.maxDistance() + (collision.capCells() + 2) * collision.cellSize() + map.voxelSize(),
                       map.voxelSize());
  }
  std::vector<uint8_t> reused(voxels.size(), 0);
  parallelForChunked(voxels.size(), config_.threads, 64, [&](size_t i) {
    Ise& ise = out->ises[i];
    ise.voxel = voxels[i];
    ise.id = grid.voxelId(voxels[i]);
    ise.position = grid.voxelCenter(voxels[i]);
    const auto kept =
        keep && !near[grid.blockSlot(TsdfMap::blockOfVoxel(voxels[i]))] ? poses_.find(ise.id) : poses_.end();
    if (kept != poses_.end()) {
      ise.direction = kept->second.direction;
      (*searches)[i] = kept->second.search;
      (*poses)[i] = kept->second.pose;
      reused[i] = 1;
    } else {
      ise.direction = generator_.direction(grid, voxels[i]);
      (*searches)[i] =
          generator_.generate(rays, collision, bounds, voxels[i], ise.direction, &(*poses)[i], approach);
    }
    (*poses)[i].sources.assign(1, static_cast<uint32_t>(i));
  });
  if (!reuse_poses_) return;
  std::unordered_map<uint64_t, KeptPose> next;
  next.reserve(voxels.size());
  for (size_t i = 0; i < voxels.size(); ++i) {
    out->stats.poses_reused += reused[i];
    next.emplace(out->ises[i].id, KeptPose{out->ises[i].direction, (*searches)[i], (*poses)[i]});
  }
  poses_ = std::move(next);
  kept_build_ = collision.buildId();
}

void FrontierBuilder::evaluateViews(bool keep, double voxel_size, const VoxelRayCaster& rays,
                                    const VoxelRayCaster& loose, Frontier* out) {
  std::vector<Viewpoint>& views = out->viewpoints;
  const VoxelStateGrid& grid = extractor_.states();
  std::vector<uint8_t> todo(views.size(), 1);
  std::vector<const KeptView*> kept(views.size(), nullptr);
  if (keep && !views_.empty()) {
    // C_q reads the states within max_range of q, and an ISE's status its
    // neighbours' states (one voxel more).
    const std::vector<uint8_t> near = nearChanges(config_.camera.max_range + 2.0 * voxel_size, voxel_size);
    std::unordered_map<uint64_t, uint32_t> index_of;
    index_of.reserve(out->ises.size());
    for (size_t i = 0; i < out->ises.size(); ++i) index_of.emplace(out->ises[i].id, static_cast<uint32_t>(i));
    for (size_t i = 0; i < views.size(); ++i) {
      Eigen::Vector3i v;
      if (!grid.voxelOf(views[i].position, &v) || near[grid.blockSlot(TsdfMap::blockOfVoxel(v))]) continue;
      const auto it = views_.find(keyOf(views[i]));
      if (it == views_.end()) continue;
      std::vector<uint32_t> visible;
      visible.reserve(it->second.visible.size());
      bool all = true;
      for (uint64_t id : it->second.visible) {
        const auto at = index_of.find(id);
        if (at == index_of.end()) {
          all = false;
          break;
        }
        visible.push_back(at->second);
      }
      if (!all) continue;
      std::sort(visible.begin(), visible.end());
      views[i].visible = std::move(visible);
      todo[i] = 0;
      kept[i] = &it->second;
    }
  }
  std::vector<uint64_t> steps;
  out->stats.voxel_steps = visibility_.evaluate(rays, out->ises, &views, &todo, &steps);
  for (size_t i = 0; i < views.size(); ++i) {
    if (!kept[i]) continue;
    steps[i] = kept[i]->steps;
    out->stats.voxel_steps += steps[i];
    views[i].unknown_fraction = kept[i]->unknown_fraction;
    ++out->stats.views_reused;
  }
  if (config_.unknown_fraction) {
    parallelForChunked(views.size(), config_.threads, 16, [&](size_t i) {
      if (todo[i]) views[i].unknown_fraction = unknownFraction(loose, views[i], config_.camera);
    });
  }
  if (!reuse_poses_) return;
  std::unordered_map<ViewKey, KeptView, ViewKeyHash> next;
  next.reserve(views.size());
  for (size_t i = 0; i < views.size(); ++i) {
    KeptView k;
    k.visible.reserve(views[i].visible.size());
    for (uint32_t j : views[i].visible) k.visible.push_back(out->ises[j].id);
    k.steps = steps[i];
    k.unknown_fraction = views[i].unknown_fraction;
    next.emplace(keyOf(views[i]), std::move(k));
  }
  views_ = std::move(next);
}

FrontierBuilder::FrontierBuilder(const SurfaceConfig& config)
    : config_(config),
      extractor_(config.threads),
      generator_(config),
      merger_(config),
      visibility_(config),
      clusterer_(config) {}

Status FrontierBuilder::update(const TsdfMap& map, const CollisionMap& collision, Frontier* frontier) {
  const int f = collision.voxelsPerCell();
  const Eigen::Vector3i cells = (map.gridVoxels().array() + f - 1) / f;
  if (collision.gridCells() != cells || std::abs(collision.cellSize() - f * map.voxelSize()) > 1e-9) {
    return Status::Error("collision map does not match the TSDF map's grid (was it built from this map?)");
  }
  const Clock::time_point t0 = Clock::now();
  Frontier out;
  FrontierStats& stats = out.stats;
  const IseUpdateStats ise_stats = extractor_.update(map);
  stats.full_extraction = ise_stats.full;
  stats.blocks_changed = ise_stats.blocks_changed;
  stats.blocks_examined = ise_stats.blocks_examined;
  out.scanned = extractor_.scannedCount();
  out.map_stamp = map.changeCounter();
  const VoxelStateGrid& grid = extractor_.states();
  const AlignedBox& bounds = map.config().bounds;
  const Clock::time_point t1 = Clock::now();

  // One pose per ISE (eq. 2 and the fall-backs).
  const VoxelRayCaster rays(grid, config_.unknown_blocks_visibility);
  const VoxelRayCaster loose(grid, false);
  const VoxelRayCaster* approach = config_.approach_range_fraction > 0.0 ? &loose : nullptr;
  // What the last update found may be kept (see frontier_builder.h): not
  // after a full extraction, nor on another collision map build.
  const bool keep = reuse_poses_ && !ise_stats.full && collision.buildId() == kept_build_;
  std::vector<Viewpoint> poses;
  std::vector<PoseSearch> searches;
  searchPoses(map, collision, keep && !poses_.empty(), rays, approach, &poses, &searches, &out);
  const size_t n_ises = out.ises.size();
  std::vector<Viewpoint> accepted;
  std::vector<uint32_t> accepted_ise;
  accepted.reserve(n_ises);
  for (size_t i = 0; i < n_ises; ++i) {
    stats.poses_tested += static_cast<size_t>(searches[i].tested);
    if (!searches[i].found) {
      out.ises[i].remaining = true;
      out.ises[i].unknown_blocked = searches[i].unknown_blocked;
      ++out.remaining;
      out.remaining_unknown += searches[i].unknown_blocked ? 1 : 0;
      continue;
    }
    if (searches[i].tested > 1) ++stats.fallback_poses;
    out.ises[i].approach = searches[i].approach;
    stats.approach_poses += searches[i].approach ? 1 : 0;
    accepted.push_back(std::move(poses[i]));
    accepted_ise.push_back(static_cast<uint32_t>(i));
  }
  stats.unmerged_viewpoints = accepted.size();
  const Clock::time_point t2 = Clock::now();

  std::vector<int> group_of;
  out.viewpoints = merger_.merge(accepted, collision, bounds, &group_of);
  for (size_t k = 0; k < accepted_ise.size(); ++k) out.ises[accepted_ise[k]].viewpoint = group_of[k];
  const Clock::time_point t3 = Clock::now();

  evaluateViews(keep, map.voxelSize(), rays, loose, &out);
  if (stats.approach_poses > 0) addApproachSources(out.ises, &out.viewpoints);
  const Clock::time_point t4 = Clock::now();

  std::vector<std::pair<int, int>> links;
  out.clusters = clusterer_.cluster(collision, out.ises.size(), &out.viewpoints, &links);
  stats.links = links.size();
  const Clock::time_point t5 = Clock::now();

  stats.ise_ms = msBetween(t0, t1);
  stats.viewpoints_ms = msBetween(t1, t2);
  stats.merge_ms = msBetween(t2, t3);
  stats.visibility_ms = msBetween(t3, t4);
  stats.clusters_ms = msBetween(t4, t5);
  stats.total_ms = msBetween(t0, t5);
  *frontier = std::move(out);
  return Status::Ok();
}

}  // namespace surface_nbv
