// The mapping loop on the box scene: tsdf/update keeps a MapMirror in step,
// the mesh marker arrives, and the exported mesh lies on the box.
#include <gtest/gtest.h>

#include <algorithm>
#include <mutex>

#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <sensor_msgs/Image.h>
#include <visualization_msgs/Marker.h>

#include "surface_nbv/FilePath.h"
#include "surface_nbv/NodeStats.h"
#include "surface_nbv/TsdfUpdate.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/map_conversions.h"
#include "surface_nbv/ros/mapper_params.h"
#include "surface_nbv/sim/mesh_io.h"

using namespace surface_nbv;

namespace {

// Distance from p to the surface of the box [-2, 2] x [-2, 2] x [0, 4].
double distanceToBox(const Eigen::Vector3d& p) {
  const Eigen::Vector3d lo(-2, -2, 0), hi(2, 2, 4);
  const Eigen::Vector3d q = p.cwiseMax(lo).cwiseMin(hi);
  if ((q - p).norm() > 0) return (q - p).norm();
  return std::min((p - lo).minCoeff(), (hi - p).minCoeff());
}

uint64_t counter(const NodeStats& s, const std::string& name) {
  for (const auto& c : s.counters) {
    if (c.name == name) return c.count;
  }
  return 0;
}

}  // namespace

TEST(TsdfMapperLoop, MirrorFollowsAndMeshLiesOnTheBox) {
  ros::NodeHandle nh;
  // The shared map parameters, read as the nodes read them (one copy, never disagreeing).
  TsdfConfig config;
  const Status shared = loadSharedMapConfig("/nbv", &config);
  ASSERT_TRUE(shared.ok()) << shared.message();
  MapMirror mirror(config);
  std::mutex mutex;
  size_t triangles = 0, updates = 0, snapshots_asked = 0;
  NodeStats stats;
  ros::ServiceClient snapshot = nh.serviceClient<std_srvs::Trigger>("tsdf_mapper/request_snapshot");
  ros::Subscriber update_sub = nh.subscribe<TsdfUpdate>("tsdf/update", 100, [&](const TsdfUpdateConstPtr& msg) {
    MapUpdate update;
    fromUpdateMsg(*msg, &update);
    std::lock_guard<std::mutex> l(mutex);
    ++updates;
    if (mirror.apply(update) == ApplyResult::kNeedSnapshot) {
      std_srvs::Trigger t;
      snapshot.call(t);
      ++snapshots_asked;
    }
  });
  ros::Subscriber mesh_sub = nh.subscribe<visualization_msgs::Marker>(
      "tsdf/mesh", 1, [&](const visualization_msgs::MarkerConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        triangles = m->points.size() / 3;
      });
  ros::Subscriber stats_sub = nh.subscribe<NodeStats>("tsdf/stats", 1, [&](const NodeStatsConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex);
    stats = *m;
  });
  ros::Publisher bad_pub = nh.advertise<sensor_msgs::Image>("depth/image", 5);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  // Wrong encodings and sizes among the simulator's frames are counted drops.
  // They are sent once the mapper integrates frames: before its first
  // camera_info any image counts as no_camera_info, not bad_image.
  for (int i = 0; i < 600; ++i) {
    {
      std::lock_guard<std::mutex> l(mutex);
      if (bad_pub.getNumSubscribers() > 0 && counter(stats, "frames_integrated") > 0) break;
    }
    ros::WallDuration(0.1).sleep();
  }
  sensor_msgs::Image bad;
  bad.header.frame_id = "camera";
  bad.header.stamp = ros::Time::now();
  bad.encoding = "rgb8";
  bad.width = 4;
  bad.height = 4;
  bad.step = 12;
  bad.data.assign(48, 0);
  bad_pub.publish(bad);
  bad.encoding = "32FC1";
  bad.step = 3;  // too small for 4 floats a row
  bad_pub.publish(bad);
  // 25 s of wall time at 4x: about one loop around the box at two heights.
  ros::WallDuration(25.0).sleep();

  {
    std::lock_guard<std::mutex> l(mutex);
    EXPECT_TRUE(mirror.synced());
    EXPECT_GT(updates, 10u);
    EXPECT_GT(mirror.map().numBlocks(), 10u);
    EXPECT_GT(triangles, 500u) << "no mesh on tsdf/mesh";
    EXPECT_GT(counter(stats, "frames_integrated"), 300u);
    EXPECT_EQ(counter(stats, "dropped_bad_image"), 2u);
    EXPECT_EQ(counter(stats, "dropped_integration"), 0u);
    // The level camera agrees with the config's camera/pitch_deg (0).
    EXPECT_TRUE(std::any_of(stats.counters.begin(), stats.counters.end(),
                            [](const auto& c) { return c.name == "camera_pitch_mismatch"; }));
    EXPECT_EQ(counter(stats, "camera_pitch_mismatch"), 0u);
  }

  ros::ServiceClient export_mesh = nh.serviceClient<FilePath>("tsdf_mapper/export_mesh");
  ASSERT_TRUE(export_mesh.waitForExistence(ros::Duration(5.0)));
  FilePath srv;
  srv.request.path = "../escape.ply";
  ASSERT_TRUE(export_mesh.call(srv));
  EXPECT_EQ(srv.response.code, 1) << "a path with '..' was accepted";
  srv.request.path = "box_loop_test.ply";
  ASSERT_TRUE(export_mesh.call(srv));
  ASSERT_EQ(srv.response.code, 0) << srv.response.message;
  // The mesh lands in the mapper's map_directory (explore_sim.launch sets it to out_dir).
  std::string directory;
  ASSERT_TRUE(nh.getParam("tsdf_mapper/map_directory", directory)) << "tsdf_mapper/map_directory is not set";
  TriangleMesh mesh;
  ASSERT_TRUE(loadMesh(directory + "/box_loop_test.ply", MeshLoadOptions(), &mesh).ok()) << directory;
  ASSERT_GT(mesh.numTriangles(), 500u);
  double worst = 0.0;
  size_t within_voxel = 0;
  for (const Eigen::Vector3f& v : mesh.vertices) {
    const double d = distanceToBox(v.cast<double>());
    worst = std::max(worst, d);
    within_voxel += d <= config.voxel_size ? 1 : 0;
  }
  // Projective TSDF thickens convex edges seen obliquely by up to the
  // truncation distance (3 voxels); everywhere else the mesh is on the box.
  EXPECT_GT(static_cast<double>(within_voxel) / mesh.vertices.size(), 0.97);
  EXPECT_LE(worst, 3 * config.voxel_size + 1e-6) << "a mesh vertex lies beyond the truncation band";
  // The four sides (64 m^2) are seen from two heights; most of them is meshed.
  EXPECT_GT(mesh.area(), 0.6 * 64.0);
  EXPECT_LT(mesh.area(), 1.1 * 80.0);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_tsdf_mapper_loop");
  return RUN_ALL_TESTS();
}
