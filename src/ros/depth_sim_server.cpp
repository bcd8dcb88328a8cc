#include "surface_nbv/ros/depth_sim_server.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>

#include <visualization_msgs/Marker.h>

#include "surface_nbv/ros/depth_conversions.h"
#include "surface_nbv/sensor/depth_points.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/util/safe_file_name.h"

namespace surface_nbv {
namespace {

// The view frustum of `camera` in its optical frame (z forward, x right,
// y down): apex to the near plane (z = min_range), the near and far
// (z = max_range) rectangles, and their four connecting edges.
visualization_msgs::Marker frustumMarker(const CameraConfig& camera, const std::string& frame) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;  // stamp 0: rviz draws it at the latest TF
  m.ns = "frustum";
  m.type = visualization_msgs::Marker::LINE_LIST;
  m.action = visualization_msgs::Marker::ADD;
  m.frame_locked = true;  // re-transformed every frame, so it follows the camera
  m.pose.orientation.w = 1.0;
  m.scale.x = 0.03;
  m.color.r = 0.3f, m.color.g = 0.85f, m.color.b = 1.0f, m.color.a = 0.7f;
  const double tx = std::tan(0.5 * camera.hfov_deg * M_PI / 180.0);
  const double ty = std::tan(0.5 * camera.vfov_deg * M_PI / 180.0);
  auto corner = [&](double z, int i) {
    geometry_msgs::Point p;
    p.x = (i == 0 || i == 3 ? -tx : tx) * z;
    p.y = (i < 2 ? -ty : ty) * z;
    p.z = z;
    return p;
  };
  const geometry_msgs::Point apex;
  auto segment = [&m](const geometry_msgs::Point& a, const geometry_msgs::Point& b) {
    m.points.push_back(a);
    m.points.push_back(b);
  };
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    segment(apex, corner(camera.min_range, i));
    segment(corner(camera.min_range, i), corner(camera.min_range, j));
    segment(corner(camera.max_range, i), corner(camera.max_range, j));
    segment(corner(camera.min_range, i), corner(camera.max_range, i));
  }
  return m;
}

// Creates `dir` (and its parents) if it is missing; an error if it still is
// not a directory afterwards (a file of that name, no permission).
Status prepareExportDirectory(const std::string& dir) {
  std::error_code create_error, check_error;
  std::filesystem::create_directories(dir, create_error);
  if (std::filesystem::is_directory(dir, check_error)) return Status::Ok();
  return Status::Error("export_directory '" + dir + "' is not a directory and cannot be created" +
                       (create_error ? ": " + create_error.message() : ""));
}

// saveMesh writes `path`.tmp and renames it: a symbolic link planted at that
// name would be followed, so it is refused like one at `path` itself.
bool hasMeshExtension(const std::string& name) {
  const size_t dot = name.rfind('.');
  if (dot == std::string::npos) return false;
  std::string ext = name.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == "ply" || ext == "stl";
}

}  // namespace

DepthSimServer::DepthSimServer(ros::NodeHandle nh, ros::NodeHandle priv, const CameraConfig& camera,
                               const DepthSimConfig& config)
    : nh_(nh),
      priv_(priv),
      camera_(camera),
      config_(config),
      tf_listener_(tf_buffer_),
      stats_(priv_, "stats", "depth_sim", config.stats_period),
      pose_error_(config.pose_error) {
  status_ = prepareExportDirectory(config_.export_directory);
  if (status_) status_ = loadScene(config_.scene, &mesh_);
  if (status_) status_ = RaycastScene::create(mesh_, &scene_);
  if (!status_) return;
  renderer_ = std::make_unique<DepthRenderer>(*scene_, camera_, config_.render_threads);
  const AlignedBox b = mesh_.bounds();
  ROS_INFO("depth_sim: scene '%s', %zu triangles, bounds [%.1f %.1f %.1f] - [%.1f %.1f %.1f] m; camera %dx%d, "
           "%.0fx%.0f deg, range [%.2f, %.2f] m, %.1f Hz; ~export_scene writes into %s",
           config_.scene.scene.c_str(), mesh_.numTriangles(), b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(),
           b.max.z(), camera.width, camera.height, camera.hfov_deg, camera.vfov_deg, camera.min_range,
           camera.max_range, camera.rate_hz, config_.export_directory.c_str());

  image_pub_ = nh_.advertise<sensor_msgs::Image>("depth/image", 2);
  info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>("depth/camera_info", 2);
  if (config_.publish_points) points_pub_ = nh_.advertise<sensor_msgs::PointCloud2>("depth/points", 2);
  mesh_pub_ = priv_.advertise<visualization_msgs::Marker>("ground_truth", 1, true);
  visualization_msgs::Marker marker;
  std_msgs::Header header;
  header.frame_id = config_.world_frame;
  toMeshMarker(mesh_, header, "ground_truth", &marker);
  // Translucent blue, so that the grey reconstruction shows through it.
  marker.color.r = 0.3f;
  marker.color.g = 0.5f;
  marker.color.b = 1.0f;
  marker.color.a = 0.3f;
  mesh_pub_.publish(marker);
  frustum_pub_ = priv_.advertise<visualization_msgs::Marker>("frustum", 1, true);
  frustum_pub_.publish(frustumMarker(camera, config_.camera_frame));
  export_srv_ = priv_.advertiseService("export_scene", &DepthSimServer::exportScene, this);
  timer_ = nh_.createTimer(ros::Duration(1.0 / camera.rate_hz), &DepthSimServer::onTimer, this);
}

bool DepthSimServer::lookupPose(const ros::Time& stamp, Transform* T_W_C) {
  geometry_msgs::TransformStamped tf;
  try {
    tf = tf_buffer_.lookupTransform(config_.world_frame, config_.camera_frame, stamp,
                                    ros::Duration(config_.tf_timeout));
  } catch (const tf2::TransformException& e) {
    stats_.count("dropped_no_transform");
    ROS_WARN_THROTTLE(5.0, "depth_sim: no transform %s -> %s at %.3f, frame dropped (%lu so far): %s",
                      config_.world_frame.c_str(), config_.camera_frame.c_str(), stamp.toSec(),
                      static_cast<unsigned long>(stats_.get("dropped_no_transform")), e.what());
    return false;
  }
  if (Status s = fromTransformMsg(tf.transform, T_W_C); !s) {
    stats_.count("dropped_bad_transform");
    ROS_WARN_THROTTLE(5.0, "depth_sim: transform %s -> %s rejected, frame dropped: %s", config_.world_frame.c_str(),
                      config_.camera_frame.c_str(), s.message().c_str());
    return false;
  }
  return true;
}

void DepthSimServer::onTimer(const ros::TimerEvent&) {
  const ros::Time stamp = ros::Time::now();
  if (stamp.isZero()) {
    stats_.count("waiting_for_clock");
    return;
  }
  if (stamp <= last_stamp_) {
    stats_.count("dropped_time_not_advancing");
    return;
  }
  Transform T_W_C;
  if (!lookupPose(stamp, &T_W_C)) return;
  last_stamp_ = stamp;

  const auto t0 = std::chrono::steady_clock::now();
  DepthImage depth;
  // TF carries the odometry's estimate, fused by the mapper as this frame's
  // pose T_W_C = T_estimate J: the camera truly is at D T_estimate.
  const uint64_t frame = frame_index_++;
  Transform T_render = T_W_C;
  if (pose_error_.enabled()) {
    pose_error_.advance(T_W_C.translation(), frame);
    const Transform jitter = T_W_C.inverse() * pose_error_.reportedPose(T_W_C, frame);
    T_render = pose_error_.truePose(T_W_C * jitter.inverse());
  }
  renderer_->render(T_render, &depth, frame);
  stats_.recordMs(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());

  std_msgs::Header header;
  header.stamp = stamp;
  header.frame_id = config_.camera_frame;
  sensor_msgs::CameraInfo info;
  toCameraInfoMsg(camera_, header, &info);
  sensor_msgs::Image image;
  if (config_.encoding == "16UC1") {
    toImageMsgMillimetres(depth, header, &image);
  } else {
    toImageMsg(depth, header, &image);
  }
  image_pub_.publish(image);
  info_pub_.publish(info);
  if (config_.publish_points && points_pub_.getNumSubscribers() > 0) {
    std::vector<Eigen::Vector3f> points_C;
    depthToPoints(camera_, depth, &points_C, config_.points_stride);
    sensor_msgs::PointCloud2 cloud;
    toPointCloud2Msg(points_C, header, &cloud);
    points_pub_.publish(cloud);
  }
  stats_.count("frames_published");
}

bool DepthSimServer::exportScene(surface_nbv::FilePath::Request& req, surface_nbv::FilePath::Response& res) {
  std::string path;
  Status s = resolveFileName(config_.export_directory, req.path, false, &path);
  if (s && !hasMeshExtension(req.path)) {
    s = Status::Error("file name '" + req.path + "' expected to end in .ply or .stl");
  }
  if (!s) {
    res.code = 1;
    res.message = s.message();
    return true;
  }
  s = saveMesh(mesh_, path);
  res.code = s ? 0 : 2;
  res.message = s ? "wrote " + std::to_string(mesh_.numTriangles()) + " triangles to " + path : s.message();
  return true;
}

}  // namespace surface_nbv
