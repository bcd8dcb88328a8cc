#include "surface_nbv/ros/frontier_conversions.h"

#include <algorithm>
#include <cmath>

#include <tf2_eigen/tf2_eigen.h>

#include "surface_nbv/util/angles.h"

namespace surface_nbv {

double yawOf(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

bool allFinite(const geometry_msgs::Point& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

bool allFinite(const geometry_msgs::Quaternion& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w) &&
         q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w > 1e-12;
}

namespace {

visualization_msgs::Marker layer(const std_msgs::Header& header, const std::string& ns, int type, double scale) {
  visualization_msgs::Marker m;
  m.header = header;
  m.ns = ns;
  m.id = 0;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = scale;
  m.color.a = 1.0f;
  return m;
}

std_msgs::ColorRGBA gainColour(double t) {
  std_msgs::ColorRGBA c;
  t = std::clamp(t, 0.0, 1.0);
  c.r = static_cast<float>(t);
  c.g = static_cast<float>(0.2 + 0.6 * (1.0 - std::abs(2.0 * t - 1.0)));
  c.b = static_cast<float>(1.0 - t);
  c.a = 1.0f;
  return c;
}

}  // namespace

void toFrontierMsg(const Frontier& frontier, const std_msgs::Header& header, surface_nbv::SurfaceFrontier* msg) {
  msg->header = header;
  msg->ises.clear();
  msg->remaining.clear();
  for (size_t i = 0; i < frontier.ises.size(); ++i) {
    msg->ises.push_back(tf2::toMsg(frontier.ises[i].position));
    if (frontier.ises[i].remaining) msg->remaining.push_back(static_cast<uint32_t>(i));
  }
  msg->viewpoints.clear();
  for (const Viewpoint& v : frontier.viewpoints) {
    surface_nbv::FrontierViewpoint out;
    out.pose.position = tf2::toMsg(v.position);
    out.pose.orientation.w = std::cos(0.5 * v.yaw);
    out.pose.orientation.z = std::sin(0.5 * v.yaw);
    out.visible_ises.assign(v.visible.begin(), v.visible.end());
    out.sources.assign(v.sources.begin(), v.sources.end());
    out.unknown_fraction = v.unknown_fraction;
    msg->viewpoints.push_back(out);
  }
  msg->clusters.clear();
  for (const Cluster& c : frontier.clusters) {
    surface_nbv::FrontierCluster out;
    out.viewpoints.assign(c.viewpoints.begin(), c.viewpoints.end());
    out.gain = c.gain;
    msg->clusters.push_back(out);
  }
  msg->num_ises = static_cast<uint32_t>(frontier.ises.size());
  msg->num_remaining = static_cast<uint32_t>(frontier.remaining);
  msg->num_scanned = frontier.scanned;
  const FrontierStats& s = frontier.stats;
  msg->stage_names = {"ises", "viewpoints", "merge", "visibility", "clusters", "total"};
  msg->stage_ms = {s.ise_ms, s.viewpoints_ms, s.merge_ms, s.visibility_ms, s.clusters_ms, s.total_ms};
}

void toFrontierMarkers(const Frontier& frontier, const std_msgs::Header& header, double voxel_size,
                       visualization_msgs::MarkerArray* markers) {
  using visualization_msgs::Marker;
  Marker ises = layer(header, "ises", Marker::CUBE_LIST, voxel_size);
  ises.color.r = 1.0f, ises.color.g = 0.8f, ises.color.b = 0.1f;
  Marker remaining = layer(header, "remaining", Marker::CUBE_LIST, voxel_size);
  remaining.color.r = 0.9f, remaining.color.g = 0.1f, remaining.color.b = 0.1f;
  for (const Ise& ise : frontier.ises) (ise.remaining ? remaining : ises).points.push_back(tf2::toMsg(ise.position));
  Marker arrows = layer(header, "viewpoints", Marker::LINE_LIST, 0.05);
  arrows.color.r = 0.1f, arrows.color.g = 0.9f, arrows.color.b = 0.2f;
  Marker members = layer(header, "clusters", Marker::SPHERE_LIST, 0.4);
  double max_gain = 0.0;
  for (const Cluster& c : frontier.clusters) max_gain = std::max(max_gain, c.gain);
  for (const Viewpoint& v : frontier.viewpoints) {
    arrows.points.push_back(tf2::toMsg(v.position));
    arrows.points.push_back(tf2::toMsg(Eigen::Vector3d(v.position + v.view_direction)));
    members.points.push_back(tf2::toMsg(v.position));
    const double gain = v.cluster >= 0 && static_cast<size_t>(v.cluster) < frontier.clusters.size()
                            ? frontier.clusters[static_cast<size_t>(v.cluster)].gain
                            : 0.0;
    members.colors.push_back(gainColour(max_gain > 0.0 ? gain / max_gain : 0.0));
  }
  markers->markers.clear();
  for (Marker* m : {&ises, &remaining, &arrows, &members}) {
    if (m->points.empty()) m->action = Marker::DELETE;  // an empty list would be refused by rviz
    markers->markers.push_back(*m);
  }
}

Status fromFrontierMsg(const surface_nbv::SurfaceFrontier& msg, Frontier* frontier) {
  *frontier = Frontier();
  frontier->ises.resize(msg.ises.size());
  for (size_t i = 0; i < msg.ises.size(); ++i) {
    if (!allFinite(msg.ises[i])) return Status::Error("ise " + std::to_string(i) + " is not finite");
    frontier->ises[i].position = Eigen::Vector3d(msg.ises[i].x, msg.ises[i].y, msg.ises[i].z);
  }
  for (uint32_t r : msg.remaining) {
    if (r >= msg.ises.size()) return Status::Error("remaining index " + std::to_string(r) + " out of range");
    frontier->ises[r].remaining = true;
  }
  frontier->remaining = msg.remaining.size();
  frontier->scanned = msg.num_scanned;
  frontier->viewpoints.resize(msg.viewpoints.size());
  for (size_t i = 0; i < msg.viewpoints.size(); ++i) {
    const surface_nbv::FrontierViewpoint& in = msg.viewpoints[i];
    if (!allFinite(in.pose.position) || !allFinite(in.pose.orientation)) {
      return Status::Error("viewpoint " + std::to_string(i) + " has a non-finite pose");
    }
    Viewpoint& v = frontier->viewpoints[i];
    v.position = Eigen::Vector3d(in.pose.position.x, in.pose.position.y, in.pose.position.z);
    v.yaw = yawOf(in.pose.orientation);
    v.view_direction = Eigen::Vector3d(std::cos(v.yaw), std::sin(v.yaw), 0.0);
    for (uint32_t k : in.visible_ises) {
      if (k >= msg.ises.size()) return Status::Error("viewpoint " + std::to_string(i) + " sees ISE out of range");
    }
    v.visible.assign(in.visible_ises.begin(), in.visible_ises.end());
    for (uint32_t k : in.sources) {
      if (k >= msg.ises.size()) return Status::Error("viewpoint " + std::to_string(i) + " source ISE out of range");
      frontier->ises[k].viewpoint = static_cast<int32_t>(i);
    }
    v.sources.assign(in.sources.begin(), in.sources.end());
    if (!(in.unknown_fraction >= 0.0 && in.unknown_fraction <= 1.0)) {
      return Status::Error("viewpoint " + std::to_string(i) + " unknown_fraction not in [0, 1]");
    }
    v.unknown_fraction = in.unknown_fraction;
  }
  frontier->clusters.resize(msg.clusters.size());
  for (size_t c = 0; c < msg.clusters.size(); ++c) {
    const surface_nbv::FrontierCluster& in = msg.clusters[c];
    if (in.viewpoints.empty()) return Status::Error("cluster " + std::to_string(c) + " is empty");
    if (!std::isfinite(in.gain) || in.gain < 0.0) return Status::Error("cluster " + std::to_string(c) + " gain");
    for (uint32_t k : in.viewpoints) {
      if (k >= msg.viewpoints.size()) {
        return Status::Error("cluster " + std::to_string(c) + " viewpoint index out of range");
      }
      if (frontier->viewpoints[k].cluster >= 0) {
        return Status::Error("viewpoint " + std::to_string(k) + " is in two clusters");
      }
      frontier->viewpoints[k].cluster = static_cast<int32_t>(c);
    }
    frontier->clusters[c].viewpoints.assign(in.viewpoints.begin(), in.viewpoints.end());
    frontier->clusters[c].gain = in.gain;
  }
  return Status::Ok();
}

std::vector<Eigen::Vector4d> resamplePath(const std::vector<Eigen::Vector4d>& path, double spacing) {
  std::vector<Eigen::Vector4d> out;
  for (const Eigen::Vector4d& q : path) {
    Eigen::Vector4d p = q;
    p.w() = wrapAngle(p.w());
    if (out.empty()) {
      out.push_back(p);
      continue;
    }
    const Eigen::Vector4d a = out.back();
    const double length = (p.head<3>() - a.head<3>()).norm();
    const double dyaw = wrapAngle(p.w() - a.w());
    if (length < 1e-9 && std::abs(dyaw) < 1e-9) continue;
    const int steps = std::max(1, static_cast<int>(std::ceil(length / spacing)));
    for (int s = 1; s <= steps; ++s) {
      const double t = static_cast<double>(s) / steps;
      Eigen::Vector4d r;
      r.head<3>() = a.head<3>() + t * (p.head<3>() - a.head<3>());
      r.w() = wrapAngle(a.w() + t * dyaw);
      out.push_back(r);
    }
  }
  return out;
}

}  // namespace surface_nbv
