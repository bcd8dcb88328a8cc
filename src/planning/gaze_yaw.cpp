#include "surface_nbv/planning/gaze_yaw.h"

#include <algorithm>
#include <cmath>

#include "surface_nbv/map/collision_map.h"
#include "surface_nbv/util/angles.h"

namespace surface_nbv {

namespace {

constexpr double kDeg = M_PI / 180.0;

bool finitePositive(double x) { return std::isfinite(x) && x > 0.0; }

// A target the camera at p could see at some yaw: in range, on its free
// side, with a clear line of sight. Writes its azimuth, horizontal distance
// and height above p.
struct Candidate {
  double azimuth, horizontal, dz;
};

bool lineOfSight(const CollisionMap& map, const Eigen::Vector3d& p, const Eigen::Vector3d& v, double end_margin) {
  const Eigen::Vector3d d = v - p;
  const double length = d.norm() - end_margin;
  const double step = 0.5 * map.cellSize();
  for (double s = step; s < length; s += step) {
    if (map.distance(p + d * (s / (length + end_margin))) <= 0.0) return false;
  }
  return true;
}

void candidates(const GazeConfig& c, const std::vector<GazeTarget>& targets, const CollisionMap* map,
                const Eigen::Vector3d& p, std::vector<Candidate>* out) {
  out->clear();
  const double half_v = 0.5 * c.camera.vfov_deg * kDeg, pitch = c.camera.pitch_deg * kDeg;
  const double min_above = c.camera.minPoseElevationDeg() * kDeg, max_above = c.camera.maxPoseElevationDeg() * kDeg;
  const double tan_h = std::tan(0.5 * c.camera.hfov_deg * kDeg), cos_h = std::cos(0.5 * c.camera.hfov_deg * kDeg);
  const double corner = c.camera.max_range * std::sqrt(1.0 + tan_h * tan_h + std::tan(half_v) * std::tan(half_v));
  for (const GazeTarget& t : targets) {
    const Eigen::Vector3d d = t.position - p;
    const double h = d.head<2>().norm();
    // Necessary at some yaw: the depth is largest when the yaw faces the
    // target; p's elevation above it lies in the camera's window. A level
    // camera's depth is at least h cos(hfov / 2) inside the FOV; a pitched
    // one's distance at most the far corner's.
    const double above = -std::atan2(d.z(), h);
    if (h * std::cos(pitch) - d.z() * std::sin(pitch) < c.camera.min_range) continue;
    if (above < min_above - 1e-12 || above > max_above + 1e-12) continue;
    if (pitch == 0.0 ? h * cos_h > c.camera.max_range : d.norm() > corner) continue;
    if (t.direction.dot(-d) <= 0.0) continue;  // p is behind the surface
    if (map != nullptr && !lineOfSight(*map, p, t.position, c.end_margin)) continue;
    out->push_back({std::atan2(d.y(), d.x()), h, d.z()});
  }
}

// The frustum of the camera on a level UAV (its mount pitched down by the
// camera's pitch): whether a candidate lies in it at `yaw`.
struct Frustum {
  explicit Frustum(const CameraConfig& c)
      : tan_h(std::tan(0.5 * c.hfov_deg * kDeg)), tan_v(std::tan(0.5 * c.vfov_deg * kDeg)),
        cos_p(std::cos(c.pitch_deg * kDeg)), sin_p(std::sin(c.pitch_deg * kDeg)),
        min_range(c.min_range), max_range(c.max_range) {}
  bool sees(const Candidate& a, double yaw) const {
    const double off = a.azimuth - yaw;
    const double ahead = a.horizontal * std::cos(off);  // along the yaw, level
    const double depth = ahead * cos_p - a.dz * sin_p;
    if (depth < min_range || depth > max_range) return false;
    const double down = -ahead * sin_p - a.dz * cos_p;  // along the optical y axis
    return std::abs(a.horizontal * std::sin(off)) <= depth * tan_h && std::abs(down) <= depth * tan_v;
  }
  double tan_h, tan_v, cos_p, sin_p, min_range, max_range;
};

double binYaw(const GazeConfig& c, int k) { return -M_PI + 2.0 * M_PI * k / c.yaw_bins; }

// Visible counts for the yaw_bins yaws binYaw(k).
void countBins(const GazeConfig& c, const std::vector<Candidate>& cands, std::vector<int>* counts) {
  counts->assign(static_cast<size_t>(c.yaw_bins), 0);
  const Frustum frustum(c.camera);
  for (int k = 0; k < c.yaw_bins; ++k) {
    int n = 0;
    for (const Candidate& a : cands) n += frustum.sees(a, binYaw(c, k));
    (*counts)[static_cast<size_t>(k)] = n;
  }
}

}  // namespace

Status GazeConfig::validate() const {
  if (!finitePositive(step)) return Status::Error("gaze step expected > 0");
  if (min_ises < 1) return Status::Error("gaze min_ises expected >= 1");
  if (yaw_bins < 4 || yaw_bins > 360) return Status::Error("gaze yaw_bins expected in [4, 360]");
  if (!(end_margin >= 0.0) || !std::isfinite(end_margin)) return Status::Error("gaze end_margin expected >= 0");
  if (Status s = camera.validate(); !s) return s;
  return Status::Ok();
}

std::vector<GazeTarget> gazeTargets(const Frontier& frontier) {
  std::vector<GazeTarget> out;
  out.reserve(frontier.ises.size());
  for (const Ise& e : frontier.ises) {
    if (e.remaining || !(e.direction.squaredNorm() > 0.0)) continue;
    out.push_back({e.position, e.direction});
  }
  return out;
}

int countVisible(const GazeConfig& config, const std::vector<GazeTarget>& targets, const CollisionMap* map,
                 const Eigen::Vector3d& p, double yaw) {
  std::vector<Candidate> cands;
  candidates(config, targets, map, p, &cands);
  const Frustum frustum(config.camera);
  int n = 0;
  for (const Candidate& a : cands) n += frustum.sees(a, yaw);
  return n;
}

int applyGaze(const GazeConfig& config, const std::vector<GazeTarget>& targets, const CollisionMap* map,
              double keep_end, std::vector<Eigen::Vector4d>* path) {
  std::vector<Eigen::Vector4d>& p = *path;
  if (p.size() < 2 || targets.empty()) return 0;
  std::vector<double> s(p.size(), 0.0);
  for (size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + (p[i].head<3>() - p[i - 1].head<3>()).norm();
  const double gaze_end = s.back() - keep_end;
  if (gaze_end <= config.step) return 0;
  // Vertex i looks along segment i (orientLeg); resampled points take the
  // heading of the segment they lie on.
  std::vector<Eigen::Vector4d> out;
  std::vector<bool> gaze;
  out.push_back(p.front());
  gaze.push_back(false);
  double next = config.step;
  for (size_t i = 0; i + 1 < p.size(); ++i) {
    const double seg = s[i + 1] - s[i];
    for (; next < std::min(s[i + 1], gaze_end); next += config.step) {
      if (next <= s[i]) continue;
      Eigen::Vector4d q;
      q << p[i].head<3>() + (p[i + 1].head<3>() - p[i].head<3>()) * ((next - s[i]) / seg), p[i].w();
      out.push_back(q);
      gaze.push_back(true);
    }
    out.push_back(p[i + 1]);
    gaze.push_back(i + 1 < p.size() - 1 && s[i + 1] < gaze_end);
  }
  std::vector<Candidate> cands;
  std::vector<int> counts;
  int set = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    if (!gaze[i]) continue;
    candidates(config, targets, map, out[i].head<3>(), &cands);
    if (static_cast<int>(cands.size()) < config.min_ises) continue;
    countBins(config, cands, &counts);
    const double heading = out[i].w();
    int best = -1;
    double best_turn = 0.0;
    for (int k = 0; k < config.yaw_bins; ++k) {
      const int n = counts[static_cast<size_t>(k)];
      const double turn = std::abs(wrapAngle(binYaw(config, k) - heading));
      if (best < 0 || n > counts[static_cast<size_t>(best)] ||
          (n == counts[static_cast<size_t>(best)] && turn < best_turn)) {
        best = k;
        best_turn = turn;
      }
    }
    if (counts[static_cast<size_t>(best)] < config.min_ises) continue;
    out[i].w() = binYaw(config, best);
    ++set;
  }
  p.swap(out);
  return set;
}

}  // namespace surface_nbv
