// The tsdf_mapper node: fuses depth/image (+ depth/camera_info) or
// depth/points into the TSDF at the TF pose world -> sensor of each frame's
// own stamp. Frames wait in a bounded queue for their transform (no
// extrapolation, no "latest" fallback) and are dropped, counted by reason,
// when it does not come; stamps jumping backwards (a bag restarted) reset the
// queue, and the TF buffer if it still holds poses from before the jump.
// Publishes tsdf/update (changed blocks, or a snapshot for late joiners and
// on request, with sequence numbers), tsdf/mesh and tsdf/stats; services
// ~save_map, ~load_map, ~export_mesh take a file name inside map_directory,
// ~request_snapshot forces a snapshot.
#pragma once

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "surface_nbv/FilePath.h"
#include "surface_nbv/map/mesh_extractor.h"
#include "surface_nbv/map/mesh_layer.h"
#include "surface_nbv/map/tsdf_integrator.h"
#include "surface_nbv/ros/mapper_params.h"
#include "surface_nbv/map/mount_pitch_monitor.h"
#include "surface_nbv/ros/stats_reporter.h"

namespace surface_nbv {

class TsdfMapperServer {
 public:
  TsdfMapperServer(ros::NodeHandle nh, ros::NodeHandle priv, const MapperConfig& config);

  const TsdfMap& map() const { return map_; }

 private:
  struct Frame {
    ros::Time stamp;
    std::string frame_id;
    ros::WallTime arrival;
    std::shared_ptr<DepthCamera> camera;     // image frames
    DepthImage depth;
    std::vector<Eigen::Vector3f> points;     // point frames
  };

  void onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg);
  void onImage(const sensor_msgs::ImageConstPtr& msg);
  void onPoints(const sensor_msgs::PointCloud2ConstPtr& msg);
  void enqueue(Frame frame);
  // After `frame`'s stamp jumped back: whether the TF buffer still places its
  // sensor later than the jump allows, i.e. holds the poses of before the
  // jump. Under sim time tf2_ros's listener clears the buffer when the first
  // transform after a clock jump comes; that transform belongs to the new
  // timeline and must survive the frame's reset (it may precede the frame).
  bool holdsPosesFromBeforeJump(const Frame& frame) const;
  void processPending();
  void integrate(const Frame& frame, const Transform& T_W_S);
  void drop(const std::string& reason, const std::string& detail);

  void publishUpdate();
  void publishMesh();
  // Waits for the mesh layer's fusion in flight; counts and logs a failure.
  void finishMeshLayer();
  void publishStats();
  // Writes the older of the two autosave slots (atomic: saveMap writes a
  // temporary file, syncs and renames), so the newest two snapshots remain.
  void autosave();
  // Loads the newest autosave that loads (the other one if it is damaged).
  void resumeFromAutosave();
  bool saveMap(surface_nbv::FilePath::Request& req, surface_nbv::FilePath::Response& res);
  bool loadMap(surface_nbv::FilePath::Request& req, surface_nbv::FilePath::Response& res);
  bool exportMesh(surface_nbv::FilePath::Request& req, surface_nbv::FilePath::Response& res);
  bool requestSnapshot(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  ros::NodeHandle nh_, priv_;
  MapperConfig config_;
  TsdfMap map_;
  TsdfIntegrator integrator_;
  MeshLayer mesh_layer_;  // what tsdf/mesh and export_mesh mesh (nbv/mesh_truncation)
  std::unique_ptr<MeshExtractor> mesher_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  StatsReporter stats_;
  MountPitchMonitor pitch_monitor_;  // the image frames' optical axis against camera/pitch_deg
  std::shared_ptr<DepthCamera> camera_;
  std::deque<Frame> pending_;
  ros::Time newest_stamp_;

  ros::Subscriber info_sub_, image_sub_, points_sub_;
  ros::Publisher update_pub_, mesh_pub_;
  ros::ServiceServer save_srv_, load_srv_, export_srv_, snapshot_srv_;
  ros::WallTimer pending_timer_, update_timer_, mesh_timer_, stats_timer_, autosave_timer_;
  int autosave_slot_ = 0;
  uint64_t sequence_ = 0;
  uint64_t published_stamp_ = 0;  // map change counter at the last tsdf/update
  uint64_t meshed_stamp_ = 0;
  bool snapshot_requested_ = true;
  bool start_cleared_ = false;  // start_free_radius applied
};

}  // namespace surface_nbv
