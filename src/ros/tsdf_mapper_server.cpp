#include "surface_nbv/ros/tsdf_mapper_server.h"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include <visualization_msgs/Marker.h>

#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/map_io.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/depth_conversions.h"
#include "surface_nbv/ros/map_conversions.h"
#include "surface_nbv/sim/mesh_io.h"
#include "surface_nbv/util/safe_file_name.h"

namespace surface_nbv {
namespace {

// Jumps back in time larger than this reset the queue (a bag restarted).
constexpr double kBackwardsJump = 1.0;

}  // namespace

TsdfMapperServer::TsdfMapperServer(ros::NodeHandle nh, ros::NodeHandle priv, const MapperConfig& config)
    : nh_(nh),
      priv_(priv),
      config_(config),
      map_(config.tsdf),
      integrator_(&map_),
      mesh_layer_(&map_),
      mesher_(std::make_unique<MeshExtractor>()),
      tf_listener_(tf_buffer_),
      stats_(nh_, "tsdf/stats", "tsdf_mapper", config.stats_period) {
  if (config_.input == "image") {
    info_sub_ = nh_.subscribe("depth/camera_info", config_.input_queue, &TsdfMapperServer::onCameraInfo, this);
    image_sub_ = nh_.subscribe("depth/image", config_.input_queue, &TsdfMapperServer::onImage, this);
  } else {
    points_sub_ = nh_.subscribe("depth/points", config_.input_queue, &TsdfMapperServer::onPoints, this);
  }
  update_pub_ = nh_.advertise<surface_nbv::TsdfUpdate>(
      "tsdf/update", 10, [this](const ros::SingleSubscriberPublisher&) { snapshot_requested_ = true; });
  mesh_pub_ = nh_.advertise<visualization_msgs::Marker>("tsdf/mesh", 1, true);
  save_srv_ = priv_.advertiseService("save_map", &TsdfMapperServer::saveMap, this);
  load_srv_ = priv_.advertiseService("load_map", &TsdfMapperServer::loadMap, this);
  export_srv_ = priv_.advertiseService("export_mesh", &TsdfMapperServer::exportMesh, this);
  snapshot_srv_ = priv_.advertiseService("request_snapshot", &TsdfMapperServer::requestSnapshot, this);
  pending_timer_ = nh_.createWallTimer(ros::WallDuration(0.02), [this](const ros::WallTimerEvent&) { processPending(); });
  update_timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / config_.update_rate),
                                      [this](const ros::WallTimerEvent&) { publishUpdate(); });
  if (config_.mesh_rate > 0.0) {
    mesh_timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / config_.mesh_rate),
                                      [this](const ros::WallTimerEvent&) { publishMesh(); });
  }
  stats_timer_ = nh_.createWallTimer(ros::WallDuration(config_.stats_period),
                                     [this](const ros::WallTimerEvent&) { publishStats(); });
  // A previous process of this node on the same master left its mark: this
  // is a respawn, so resume (a fresh launch never picks up old autosaves).
  const std::string session = ros::this_node::getName() + "_session";
  if (config_.resume && ros::param::has(session)) resumeFromAutosave();
  ros::param::set(session, ros::WallTime::now().toSec());
  if (config_.autosave_period > 0.0) {
    autosave_timer_ = nh_.createWallTimer(ros::WallDuration(config_.autosave_period),
                                          [this](const ros::WallTimerEvent&) { autosave(); });
  }
  const TsdfConfig& t = config_.tsdf;
  ROS_INFO("tsdf_mapper: %s input, voxel %.3f m, truncation %.3f m, W_th %.2f, bounds [%.1f %.1f %.1f] - [%.1f %.1f "
           "%.1f] (%d x %d x %d blocks), invalid pixels: %s, %d thread(s)",
           config_.input.c_str(), t.voxel_size, t.truncationDistance(), t.w_th, t.bounds.min.x(), t.bounds.min.y(),
           t.bounds.min.z(), t.bounds.max.x(), t.bounds.max.y(), t.bounds.max.z(), map_.gridBlocks().x(),
           map_.gridBlocks().y(), map_.gridBlocks().z(), toString(t.invalid_pixels), t.threads);
  if (mesh_layer_.separate()) {
    ROS_INFO("tsdf_mapper: the mesh comes from a second TSDF with truncation %.3f m", t.mesh_truncation);
  }
}

void TsdfMapperServer::drop(const std::string& reason, const std::string& detail) {
  stats_.count("dropped_" + reason);
  ROS_WARN_THROTTLE(5.0, "tsdf_mapper: frame dropped (%s): %s", reason.c_str(), detail.c_str());
}

void TsdfMapperServer::onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg) {
  DepthCamera camera(config_.camera);
  if (Status s = fromCameraInfoMsg(*msg, config_.camera, &camera); !s) {
    stats_.count("dropped_bad_camera_info");
    ROS_WARN_THROTTLE(5.0, "tsdf_mapper: %s", s.message().c_str());
    return;
  }
  if (camera_ && camera_->width() == camera.width() && camera_->height() == camera.height() &&
      camera_->fx() == camera.fx() && camera_->fy() == camera.fy() && camera_->cx() == camera.cx() &&
      camera_->cy() == camera.cy()) {
    return;
  }
  camera_ = std::make_shared<DepthCamera>(camera);
}

void TsdfMapperServer::onImage(const sensor_msgs::ImageConstPtr& msg) {
  if (!camera_) return drop("no_camera_info", "no valid depth/camera_info received yet");
  Frame f;
  if (Status s = fromImageMsg(*msg, &f.depth); !s) return drop("bad_image", s.message());
  if (f.depth.width != camera_->width() || f.depth.height != camera_->height()) {
    return drop("size_mismatch", "image " + std::to_string(f.depth.width) + "x" + std::to_string(f.depth.height) +
                                     " does not match camera_info");
  }
  f.camera = camera_;
  f.stamp = msg->header.stamp;
  f.frame_id = msg->header.frame_id;
  enqueue(std::move(f));
}

void TsdfMapperServer::onPoints(const sensor_msgs::PointCloud2ConstPtr& msg) {
  Frame f;
  if (Status s = fromPointCloud2Msg(*msg, &f.points); !s) return drop("bad_points", s.message());
  f.stamp = msg->header.stamp;
  f.frame_id = msg->header.frame_id;
  enqueue(std::move(f));
}

void TsdfMapperServer::enqueue(Frame frame) {
  if (frame.frame_id.empty()) return drop("no_frame_id", "header.frame_id is empty");
  if (frame.stamp.isZero()) return drop("zero_stamp", "header.stamp is zero");
  if (!newest_stamp_.isZero() && frame.stamp.toSec() + kBackwardsJump < newest_stamp_.toSec()) {
    ROS_WARN("tsdf_mapper: time jumped back from %.3f to %.3f s: resetting the frame queue",
             newest_stamp_.toSec(), frame.stamp.toSec());
    stats_.count("time_resets");
    stats_.count("dropped_reset", pending_.size());
    pending_.clear();
    if (holdsPosesFromBeforeJump(frame)) tf_buffer_.clear();
    newest_stamp_ = ros::Time();
  }
  newest_stamp_ = std::max(newest_stamp_, frame.stamp);
  frame.arrival = ros::WallTime::now();
  pending_.push_back(std::move(frame));
  while (static_cast<int>(pending_.size()) > config_.max_pending_frames) {
    pending_.pop_front();
    drop("queue_full", "more than " + std::to_string(config_.max_pending_frames) + " frames wait for a transform");
  }
  processPending();
}

bool TsdfMapperServer::holdsPosesFromBeforeJump(const Frame& frame) const {
  ros::Time latest;
  try {
    // Time 0: the latest time at which the whole chain is known.
    latest = tf_buffer_.lookupTransform(config_.world_frame, frame.frame_id, ros::Time(0)).header.stamp;
  } catch (const tf2::TransformException&) {
    return false;  // nothing of the chain is known: no old pose to mix in
  }
  if (latest.toSec() <= frame.stamp.toSec() + kBackwardsJump) return false;
  ROS_WARN("tsdf_mapper: the TF buffer still holds %s at %.3f s, from before the jump: clearing it",
           frame.frame_id.c_str(), latest.toSec());
  return true;
}

void TsdfMapperServer::processPending() {
  while (!pending_.empty()) {
    Frame& f = pending_.front();
    std::string error;
    if (tf_buffer_.canTransform(config_.world_frame, f.frame_id, f.stamp, &error)) {
      Transform T_W_S;
      const Status s =
          fromTransformMsg(tf_buffer_.lookupTransform(config_.world_frame, f.frame_id, f.stamp).transform, &T_W_S);
      if (s) {
        integrate(f, T_W_S);
      } else {
        drop("bad_transform", s.message());
      }
      pending_.pop_front();
      continue;
    }
    const bool too_old = error.find("past") != std::string::npos;
    const double waited = (ros::WallTime::now() - f.arrival).toSec();
    if (!too_old && waited <= config_.tf_wait) return;  // the transform may still come
    drop(too_old ? "tf_too_old" : "no_transform", error);
    pending_.pop_front();
  }
}

void TsdfMapperServer::integrate(const Frame& f, const Transform& T_W_S) {
  if (!start_cleared_ && config_.start_free_radius > 0.0) {
    // The space the UAV occupies at the first frame is free (closer than min range, unseen).
    start_cleared_ = true;
    size_t n = 0;
    Status s = integrator_.markFree(T_W_S.translation(), config_.start_free_radius, &n);
    if (s) s = mesh_layer_.markFree(T_W_S.translation(), config_.start_free_radius);
    if (!s) {
      ROS_WARN("tsdf_mapper: start_free_radius: %s", s.message().c_str());
    } else {
      ROS_INFO("tsdf_mapper: %zu unknown voxels within %.1f m of the first sensor pose marked free", n,
               config_.start_free_radius);
    }
  }
  if (f.camera) pitch_monitor_.add(T_W_S);
  const auto t0 = std::chrono::steady_clock::now();
  IntegrationStats s;
  Status layer;
  Status status;
  if (!f.camera) {
    status = integrator_.integratePoints(f.points, T_W_S, config_.camera.max_range, &s);
  } else if (mesh_layer_.busy()) {
    // The mesh layer still fuses an earlier frame on its own thread: this
    // one goes into the planning map alone, which never waits for the mesh.
    status = integrator_.integrateDepth(*f.camera, f.depth, T_W_S, &s);
    if (status) stats_.count("mesh_layer_skipped");
  } else {
    status = mesh_layer_.integrateDepthBehind(&integrator_, *f.camera, f.depth, T_W_S,
                                              std::max(2, config_.tsdf.threads), &s, &layer);
  }
  if (!status) return drop("integration", status.message());
  if (!f.camera) layer = mesh_layer_.integratePoints(f.points, T_W_S, config_.camera.max_range);
  if (!layer) {
    stats_.count("mesh_layer_failed");
    ROS_WARN_THROTTLE(10.0, "tsdf_mapper: mesh layer: %s", layer.message().c_str());
  }
  stats_.recordMs(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  stats_.count("frames_integrated");
  stats_.count("invalid_pixels", s.invalid_pixels);
  if (s.blocks_refused > 0) {
    stats_.count("blocks_refused", s.blocks_refused);
    ROS_WARN_THROTTLE(10.0, "tsdf_mapper: %zu block(s) refused: the map is at max_blocks = %zu", s.blocks_refused,
                      config_.tsdf.max_blocks);
  }
}

void TsdfMapperServer::publishUpdate() {
  const uint64_t now = map_.changeCounter();
  if (!snapshot_requested_ && now == published_stamp_) return;
  if (update_pub_.getNumSubscribers() == 0 && !snapshot_requested_) {
    published_stamp_ = now;  // nobody listens: a late joiner gets a snapshot anyway
    snapshot_requested_ = true;
    return;
  }
  MapUpdate update;
  const bool snapshot = snapshot_requested_;
  if (Status s = makeUpdate(map_, published_stamp_, ++sequence_, snapshot, &update); !s) {
    ROS_ERROR_THROTTLE(5.0, "tsdf_mapper: cannot build an update: %s", s.message().c_str());
    return;
  }
  surface_nbv::TsdfUpdate msg;
  std_msgs::Header header;
  header.stamp = newest_stamp_;
  header.frame_id = config_.world_frame;
  toUpdateMsg(update, header, &msg);
  update_pub_.publish(msg);
  stats_.count(snapshot ? "snapshots_published" : "updates_published");
  published_stamp_ = now;
  snapshot_requested_ = false;
}

void TsdfMapperServer::finishMeshLayer() {
  if (Status s = mesh_layer_.finish(); !s) {
    stats_.count("mesh_layer_failed");
    ROS_WARN_THROTTLE(10.0, "tsdf_mapper: mesh layer: %s", s.message().c_str());
  }
}

void TsdfMapperServer::publishMesh() {
  if (mesh_pub_.getNumSubscribers() == 0 || map_.changeCounter() == meshed_stamp_) return;
  meshed_stamp_ = map_.changeCounter();
  finishMeshLayer();
  mesher_->update(mesh_layer_.map());
  visualization_msgs::Marker marker;
  std_msgs::Header header;
  header.stamp = newest_stamp_;
  header.frame_id = config_.world_frame;
  toMeshMarker(mesher_->mesh(), header, "tsdf", &marker);
  mesh_pub_.publish(marker);
}

void TsdfMapperServer::publishStats() {
  size_t known = 0;
  for (const auto& b : map_.blocks()) {
    for (const TsdfVoxel& v : b->voxels) known += v.w >= config_.tsdf.w_th ? 1 : 0;
  }
  stats_.set("blocks", map_.numBlocks());
  stats_.set("known_voxels", known);
  stats_.set("pending_frames", pending_.size());
  const bool mismatch = pitch_monitor_.mismatch(config_.camera.pitch_deg);
  stats_.set("camera_pitch_mismatch", mismatch ? 1 : 0);
  if (mismatch) {
    ROS_WARN_THROTTLE(30.0,
                      "tsdf_mapper: the depth frames' optical axis is %.1f deg below the horizon on average (%zu "
                      "frames), %s/camera/pitch_deg is %.1f: the planner's views assume the latter; set it to the "
                      "camera's mount pitch",
                      pitch_monitor_.meanPitchDeg(), pitch_monitor_.frames(), config_.shared_namespace.c_str(),
                      config_.camera.pitch_deg);
  }
}

bool TsdfMapperServer::saveMap(surface_nbv::FilePath::Request& req, surface_nbv::FilePath::Response& res) {
  std::string path;
  Status s = resolveFileName(config_.map_directory, req.path, false, &path);
  if (!s) return res.code = 1, res.message = s.message(), true;
  s = surface_nbv::saveMap(map_, path);
  res.code = s ? 0 : 2;
  res.message = s ? "saved " + std::to_string(map_.numBlocks()) + " blocks to " + path : s.message();
  return true;
}

bool TsdfMapperServer::loadMap(surface_nbv::FilePath::Request& req, surface_nbv::FilePath::Response& res) {
  std::string path;
  Status s = resolveFileName(config_.map_directory, req.path, true, &path);
  if (!s) return res.code = 1, res.message = s.message(), true;
  s = surface_nbv::loadMap(path, &map_);
  if (s) {
    if (Status l = mesh_layer_.reload(path); !l) ROS_WARN("tsdf_mapper: mesh layer: %s", l.message().c_str());
    mesher_ = std::make_unique<MeshExtractor>();
    meshed_stamp_ = 0;
    snapshot_requested_ = true;
  }
  res.code = s ? 0 : 2;
  res.message = s ? "loaded " + std::to_string(map_.numBlocks()) + " blocks from " + path : s.message();
  return true;
}

bool TsdfMapperServer::exportMesh(surface_nbv::FilePath::Request& req, surface_nbv::FilePath::Response& res) {
  std::string path;
  Status s = resolveFileName(config_.map_directory, req.path, false, &path);
  if (!s) return res.code = 1, res.message = s.message(), true;
  finishMeshLayer();
  mesher_->update(mesh_layer_.map());
  meshed_stamp_ = map_.changeCounter();
  s = saveMesh(mesher_->mesh(true), path);
  res.code = s ? 0 : 2;
  res.message = s ? "wrote " + std::to_string(mesher_->mesh().numTriangles()) + " triangles to " + path : s.message();
  return true;
}

bool TsdfMapperServer::requestSnapshot(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  snapshot_requested_ = true;
  res.success = true;
  res.message = "the next tsdf/update is a snapshot";
  return true;
}

void TsdfMapperServer::autosave() {
  if (map_.numBlocks() == 0) return;
  std::error_code ec;
  std::filesystem::create_directories(config_.map_directory, ec);
  const std::string path = config_.map_directory + "/autosave_" + std::to_string(autosave_slot_) + ".tsdf";
  const auto t0 = std::chrono::steady_clock::now();
  if (Status s = surface_nbv::saveMap(map_, path); !s) {
    stats_.count("autosave_failed");
    ROS_WARN_THROTTLE(30.0, "tsdf_mapper: autosave to %s failed: %s", path.c_str(), s.message().c_str());
    return;
  }
  stats_.count("autosaves");
  ROS_DEBUG("tsdf_mapper: autosaved %zu blocks to %s in %.0f ms", map_.numBlocks(), path.c_str(),
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  autosave_slot_ = 1 - autosave_slot_;
}

void TsdfMapperServer::resumeFromAutosave() {
  std::vector<std::pair<std::filesystem::file_time_type, int>> slots;
  for (int k : {0, 1}) {
    std::error_code ec;
    const auto t = std::filesystem::last_write_time(config_.map_directory + "/autosave_" + std::to_string(k) + ".tsdf", ec);
    if (!ec) slots.emplace_back(t, k);
  }
  std::sort(slots.rbegin(), slots.rend());
  for (const auto& [time, k] : slots) {
    const std::string path = config_.map_directory + "/autosave_" + std::to_string(k) + ".tsdf";
    if (Status s = surface_nbv::loadMap(path, &map_); !s) {
      ROS_WARN("tsdf_mapper: resume: %s refused: %s", path.c_str(), s.message().c_str());
      stats_.count("resume_refused");
      continue;
    }
    if (Status l = mesh_layer_.reload(path); !l) ROS_WARN("tsdf_mapper: mesh layer: %s", l.message().c_str());
    mesher_ = std::make_unique<MeshExtractor>();
    meshed_stamp_ = 0;
    snapshot_requested_ = true;
    start_cleared_ = true;
    autosave_slot_ = 1 - k;  // keep the snapshot we resumed from
    stats_.count("resumed");
    ROS_INFO("tsdf_mapper: resumed %zu blocks from %s", map_.numBlocks(), path.c_str());
    return;
  }
  ROS_INFO("tsdf_mapper: resume: no autosave in %s, starting empty", config_.map_directory.c_str());
}

}  // namespace surface_nbv
