// Wiring of depth_sim: rate, encoding, frame, CameraInfo, depth at the pose of
// the frame time for a moving scripted TF, drops without TF, ground truth,
// and ~export_scene confined to ~export_directory.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/Marker.h>
#include <Eigen/Geometry>

#include "surface_nbv/FilePath.h"
#include "surface_nbv/NodeStats.h"
#include "surface_nbv/sim/mesh_io.h"

namespace {

// ~export_directory in depth_sim.test, and its parent.
const std::string kRoot = "/tmp/surface_nbv_depth_sim_test";
const std::string kExportDir = kRoot + "/exports";

// The names in `dir`, links not followed.
std::set<std::string> listing(const std::string& dir) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

// Camera at (x(t), 0, 2) looking along world +x towards the box face x = -2.
constexpr double kX0 = -6.0;
constexpr double kSpeed = 0.2;  // m/s along +x

struct Recorder {
  std::mutex mutex;
  std::vector<sensor_msgs::Image> images;
  std::vector<sensor_msgs::CameraInfo> infos;
  std::vector<ros::WallTime> arrival;
  size_t clouds = 0;
  surface_nbv::NodeStats stats;
  visualization_msgs::Marker ground_truth;
};

uint64_t counter(const surface_nbv::NodeStats& s, const std::string& name) {
  for (const auto& c : s.counters) {
    if (c.name == name) return c.count;
  }
  return 0;
}

float centreDepth(const sensor_msgs::Image& img) {
  // Mean of the four central pixels (cx = 319.5, cy = 239.5 lie between them).
  float sum = 0.0f;
  for (int r : {239, 240}) {
    for (int c : {319, 320}) {
      float z;
      std::memcpy(&z, &img.data[r * img.step + 4 * c], 4);
      sum += z;
    }
  }
  return sum / 4.0f;
}

class DepthSimNodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    image_sub_ = nh_.subscribe<sensor_msgs::Image>("depth/image", 50, [this](const sensor_msgs::ImageConstPtr& m) {
      std::lock_guard<std::mutex> l(rec_.mutex);
      rec_.images.push_back(*m);
      rec_.arrival.push_back(ros::WallTime::now());
    });
    info_sub_ = nh_.subscribe<sensor_msgs::CameraInfo>("depth/camera_info", 50,
                                                       [this](const sensor_msgs::CameraInfoConstPtr& m) {
                                                         std::lock_guard<std::mutex> l(rec_.mutex);
                                                         rec_.infos.push_back(*m);
                                                       });
    cloud_sub_ = nh_.subscribe<sensor_msgs::PointCloud2>("depth/points", 5, [this](const sensor_msgs::PointCloud2ConstPtr&) {
      std::lock_guard<std::mutex> l(rec_.mutex);
      ++rec_.clouds;
    });
    stats_sub_ = nh_.subscribe<surface_nbv::NodeStats>("depth_sim/stats", 5, [this](const surface_nbv::NodeStatsConstPtr& m) {
      std::lock_guard<std::mutex> l(rec_.mutex);
      rec_.stats = *m;
    });
    gt_sub_ = nh_.subscribe<visualization_msgs::Marker>("depth_sim/ground_truth", 1,
                                                        [this](const visualization_msgs::MarkerConstPtr& m) {
                                                          std::lock_guard<std::mutex> l(rec_.mutex);
                                                          rec_.ground_truth = *m;
                                                        });
  }

  void startTf() {
    t0_ = ros::Time::now();
    tf_timer_ = nh_.createWallTimer(ros::WallDuration(0.01), [this](const ros::WallTimerEvent&) {
      const ros::Time now = ros::Time::now();
      geometry_msgs::TransformStamped tf;
      tf.header.stamp = now;
      tf.header.frame_id = "world";
      tf.child_frame_id = "camera";
      tf.transform.translation.x = kX0 + kSpeed * (now - t0_).toSec();
      tf.transform.translation.z = 2.0;
      // Optical z along world +x, optical x along world -y, optical y along world -z.
      const Eigen::Matrix3d R = (Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished();
      const Eigen::Quaterniond q(R);
      tf.transform.rotation.w = q.w();
      tf.transform.rotation.x = q.x();
      tf.transform.rotation.y = q.y();
      tf.transform.rotation.z = q.z();
      broadcaster_.sendTransform(tf);
    });
  }

  ros::NodeHandle nh_;
  Recorder rec_;
  ros::Subscriber image_sub_, info_sub_, cloud_sub_, stats_sub_, gt_sub_;
  tf2_ros::TransformBroadcaster broadcaster_;
  ros::WallTimer tf_timer_;
  ros::Time t0_;
};

TEST_F(DepthSimNodeTest, DropsWithoutTfThenPublishesAtRateWithPoseOfFrameTime) {
  ros::AsyncSpinner spinner(2);
  spinner.start();
  // Wait for the node (its latched ground truth arrives once it is up).
  for (int i = 0; i < 300 && rec_.ground_truth.points.empty(); ++i) ros::WallDuration(0.1).sleep();
  ASSERT_EQ(rec_.ground_truth.points.size(), 36u) << "no ground truth marker from depth_sim";
  EXPECT_EQ(rec_.ground_truth.header.frame_id, "world");

  // Phase 1: no transform at all. Frames are dropped and counted.
  ros::WallDuration(1.5).sleep();
  {
    std::lock_guard<std::mutex> l(rec_.mutex);
    EXPECT_TRUE(rec_.images.empty()) << "published an image without a transform";
    EXPECT_GT(counter(rec_.stats, "dropped_no_transform"), 5u);
    EXPECT_EQ(counter(rec_.stats, "frames_published"), 0u);
  }

  // Phase 2: a moving scripted pose.
  startTf();
  ros::WallDuration(0.5).sleep();
  std::vector<sensor_msgs::Image> images;
  std::vector<ros::WallTime> arrival;
  {
    std::lock_guard<std::mutex> l(rec_.mutex);
    rec_.images.clear();
    rec_.arrival.clear();
  }
  ros::WallDuration(4.0).sleep();
  {
    std::lock_guard<std::mutex> l(rec_.mutex);
    images = rec_.images;
    arrival = rec_.arrival;
  }
  ASSERT_GE(images.size(), 10u);
  const double span = (arrival.back() - arrival.front()).toSec();
  const double rate = (images.size() - 1) / span;
  EXPECT_NEAR(rate, 20.0, 3.0) << images.size() << " images in " << span << " s";

  for (size_t i = 0; i < images.size(); ++i) {
    const sensor_msgs::Image& img = images[i];
    ASSERT_EQ(img.encoding, "32FC1");
    ASSERT_EQ(img.width, 640u);
    ASSERT_EQ(img.height, 480u);
    ASSERT_EQ(img.step, 640u * 4u);
    ASSERT_EQ(img.data.size(), 640u * 480u * 4u);
    EXPECT_EQ(img.header.frame_id, "camera");
    if (i > 0) {
      EXPECT_GT(img.header.stamp, images[i - 1].header.stamp);
    }
    // The depth matches the pose at the image's own stamp, not an older one.
    const double x = kX0 + kSpeed * (img.header.stamp - t0_).toSec();
    EXPECT_NEAR(centreDepth(img), -2.0 - x, 2e-3) << "image " << i;
  }

  std::lock_guard<std::mutex> l(rec_.mutex);
  ASSERT_FALSE(rec_.infos.empty());
  const sensor_msgs::CameraInfo& info = rec_.infos.back();
  EXPECT_EQ(info.header.frame_id, "camera");
  EXPECT_DOUBLE_EQ(info.K[0], 320.0);
  EXPECT_NEAR(info.K[4], 240.0 / std::tan(M_PI / 6.0), 1e-9);
  EXPECT_DOUBLE_EQ(info.K[2], 319.5);
  bool stamp_matched = false;
  for (const auto& inf : rec_.infos) stamp_matched |= inf.header.stamp == images.back().header.stamp;
  EXPECT_TRUE(stamp_matched) << "no CameraInfo with the stamp of the last image";
  EXPECT_GT(rec_.clouds, 0u);
  EXPECT_GT(counter(rec_.stats, "frames_published"), 10u);
}

// ~export_scene writes only plain names inside ~export_directory
// (depth_sim.test: kExportDir, two levels below /tmp so that the node has to
// create it; the test removes kRoot at the end). Everything else is refused
// with code 1 and a reason, and nothing is written inside or outside.
TEST_F(DepthSimNodeTest, ExportSceneWritesOnlyPlainNamesInItsDirectory) {
  namespace fs = std::filesystem;
  ros::ServiceClient client = nh_.serviceClient<surface_nbv::FilePath>("depth_sim/export_scene");
  ASSERT_TRUE(client.waitForExistence(ros::Duration(30.0)));
  ASSERT_TRUE(fs::is_directory(kExportDir)) << "depth_sim did not create its export_directory";
  // Leftovers of an earlier run, then the traps: a subdirectory, links to a
  // file outside (at a name and at the temporary name saveMesh writes first)
  // and a dangling link.
  for (const auto& e : fs::directory_iterator(kExportDir)) fs::remove_all(e.path());
  for (const auto& e : fs::directory_iterator(kRoot)) {
    if (e.path() != fs::path(kExportDir)) fs::remove_all(e.path());
  }
  fs::create_directory(kExportDir + "/a");
  const std::string kOutside = kRoot + "/outside.stl", kNowhere = kRoot + "/nowhere.stl";
  { std::ofstream(kOutside) << "not a mesh"; }
  fs::create_symlink(kOutside, kExportDir + "/link.stl");
  fs::create_symlink(kOutside, kExportDir + "/via_tmp.stl.tmp");
  fs::create_symlink(kNowhere, kExportDir + "/dangling.stl");
  const std::set<std::string> planted = listing(kExportDir);

  auto call = [&](const std::string& name, std::string* message) {
    surface_nbv::FilePath srv;
    srv.request.path = name;
    if (!client.call(srv)) return -1;
    *message = srv.response.message;
    return static_cast<int>(srv.response.code);
  };
  std::string message;
  for (const std::string name : {"scene.stl", "scene.PLY"}) {
    EXPECT_EQ(call(name, &message), 0) << name << ": " << message;
    EXPECT_NE(message.find(kExportDir + "/" + name), std::string::npos) << message;
    surface_nbv::TriangleMesh mesh;
    ASSERT_TRUE(surface_nbv::loadMesh(kExportDir + "/" + name, {}, &mesh).ok()) << name;
    EXPECT_EQ(mesh.numTriangles(), 12u) << name << ": the box scene has 12 triangles";
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(kExportDir + "/" + name))) << name;
  }

  const std::vector<std::pair<std::string, std::string>> refused = {
      {"", "empty"},
      {".", "'.'"},
      {"..", "'.'"},
      {".hidden.stl", "'.'"},
      {"../x.stl", "'.'"},
      {"a/b.stl", "path"},
      {"a/../c.stl", "path"},
      {"/tmp/surface_nbv_depth_sim_absolute.stl", "path"},
      {kRoot + "/absolute.stl", "path"},
      {"a\\b.stl", "path"},
      {"new\nline.stl", "control"},
      {std::string(200, 'x') + ".stl", "128"},
      {"a", "not a regular file"},
      {"link.stl", "symbolic link"},
      {"dangling.stl", "symbolic link"},
      {"via_tmp.stl", "temporary"},
      {"scene.obj", ".ply or .stl"},
      {"scene", ".ply or .stl"},
  };
  for (const auto& [name, reason] : refused) {
    EXPECT_EQ(call(name, &message), 1) << "'" << name << "': " << message;
    EXPECT_NE(message.find(reason), std::string::npos) << "'" << name << "': " << message;
  }

  // Nothing was written: the directory holds the two exports and the traps,
  // the parent holds the directory and the link target, unchanged; the
  // dangling link still points at nothing.
  std::set<std::string> expected = planted;
  expected.insert({"scene.stl", "scene.PLY"});
  EXPECT_EQ(listing(kExportDir), expected);
  EXPECT_EQ(listing(kExportDir + "/a"), std::set<std::string>{});
  EXPECT_EQ(listing(kRoot), (std::set<std::string>{"exports", "outside.stl"}));
  std::ifstream in(kOutside);
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "not a mesh");
  EXPECT_FALSE(fs::exists(fs::symlink_status(kNowhere)));
  EXPECT_FALSE(fs::exists(fs::symlink_status("/tmp/surface_nbv_depth_sim_absolute.stl")));
  fs::remove_all(kRoot);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_depth_sim_node");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
