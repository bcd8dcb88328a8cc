// A recorded bag replayed at 3x gives the same map as the same frames live:
// the test renders 40 depth frames of the box scene, publishes them at 10 Hz
// to /live, writes them to a bag for /replay, plays it with rosbag at 3x, and
// compares the two mappers' saved maps voxel by voxel.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <memory>

#include <ros/ros.h>
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include "surface_nbv/FilePath.h"
#include "surface_nbv/map/map_io.h"
#include "surface_nbv/ros/depth_conversions.h"
#include "surface_nbv/sim/depth_renderer.h"
#include "surface_nbv/sim/procedural_scenes.h"

using namespace surface_nbv;

namespace {

const std::string kDir = "/tmp/surface_nbv_replay_test";

struct Frame {
  sensor_msgs::Image image;
  sensor_msgs::CameraInfo info;
  tf2_msgs::TFMessage tf;
};

// Frame i for `stream` ("live" or "replay"): same pose, stamp and depth, its own camera frame name.
std::vector<Frame> makeFrames(const std::string& stream) {
  TriangleMesh mesh;
  EXPECT_TRUE(makeProceduralScene("box", &mesh).ok());
  std::unique_ptr<RaycastScene> scene;
  EXPECT_TRUE(RaycastScene::create(mesh, &scene).ok());
  CameraConfig cc;
  cc.width = 320;
  cc.height = 240;
  cc.min_range = 0.5;
  const DepthCamera camera(cc);
  const DepthRenderer renderer(*scene, camera, 2);
  std::vector<Frame> frames;
  for (int i = 0; i < 40; ++i) {
    const double a = 2 * M_PI * i / 40;
    Transform T = Transform::Identity();
    const Eigen::Vector3d pos(5.5 * std::cos(a), 5.5 * std::sin(a), 2.0);
    const Eigen::Vector3d z = -pos.normalized(), x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
    T.linear().col(0) = x;
    T.linear().col(1) = z.cross(x);
    T.linear().col(2) = z;
    T.translation() = pos;
    DepthImage depth;
    renderer.render(T, &depth);
    Frame f;
    std_msgs::Header h;
    h.stamp = ros::Time(1000.0 + 0.1 * i);
    h.frame_id = "camera_" + stream;
    toImageMsg(depth, h, &f.image);
    toCameraInfoMsg(camera, h, &f.info);
    geometry_msgs::TransformStamped tf = tf2::eigenToTransform(T);
    tf.header.stamp = h.stamp;
    tf.header.frame_id = "world";
    tf.child_frame_id = h.frame_id;
    f.tf.transforms.push_back(tf);
    frames.push_back(f);
  }
  return frames;
}

Status saveAndLoad(ros::NodeHandle& nh, const std::string& ns, TsdfMap* map) {
  ros::ServiceClient save = nh.serviceClient<FilePath>(ns + "/tsdf_mapper/save_map");
  if (!save.waitForExistence(ros::Duration(10.0))) return Status::Error(ns + ": no save_map service");
  FilePath srv;
  srv.request.path = ns + ".map";
  if (!save.call(srv) || srv.response.code != 0) return Status::Error(ns + ": " + srv.response.message);
  return loadMap(kDir + "/" + ns + ".map", map);
}

}  // namespace

TEST(TsdfMapperReplay, BagAtThreeTimesGivesTheLiveMap) {
  ros::NodeHandle nh;
  ros::Publisher tf_pub = nh.advertise<tf2_msgs::TFMessage>("/tf", 100);
  ros::Publisher image_pub = nh.advertise<sensor_msgs::Image>("live/depth/image", 100);
  ros::Publisher info_pub = nh.advertise<sensor_msgs::CameraInfo>("live/depth/camera_info", 100);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  for (int i = 0; i < 100 && (image_pub.getNumSubscribers() == 0 || tf_pub.getNumSubscribers() < 2); ++i) {
    ros::WallDuration(0.1).sleep();
  }
  ASSERT_GT(image_pub.getNumSubscribers(), 0u);

  const std::vector<Frame> replay_frames = makeFrames("replay");
  const std::string bag_path = kDir + "/frames.bag";
  {
    rosbag::Bag bag(bag_path, rosbag::bagmode::Write);
    // CameraInfo half a second ahead, so no first image can beat it.
    bag.write("/replay/depth/camera_info", ros::Time(999.5), replay_frames[0].info);
    for (const Frame& f : replay_frames) {
      bag.write("/tf", f.image.header.stamp, f.tf);
      bag.write("/replay/depth/camera_info", f.image.header.stamp, f.info);
      bag.write("/replay/depth/image", f.image.header.stamp, f.image);
    }
  }

  const std::vector<Frame> live_frames = makeFrames("live");
  info_pub.publish(live_frames[0].info);
  ros::WallDuration(0.5).sleep();
  for (const Frame& f : live_frames) {
    tf_pub.publish(f.tf);
    info_pub.publish(f.info);
    image_pub.publish(f.image);
    ros::WallDuration(0.1).sleep();
  }
  const std::string play = "rosbag play -q -r 3 " + bag_path + " > " + kDir + "/play.log 2>&1";
  ASSERT_EQ(std::system(play.c_str()), 0) << "rosbag play failed, see " << kDir << "/play.log";
  ros::WallDuration(1.5).sleep();

  TsdfConfig config;
  config.voxel_size = 0.1;
  config.bounds = AlignedBox(Eigen::Vector3d(-8, -8, -1), Eigen::Vector3d(8, 8, 6));
  TsdfMap live(config), replay(config);
  const Status s1 = saveAndLoad(nh, "live", &live);
  ASSERT_TRUE(s1.ok()) << s1.message();
  const Status s2 = saveAndLoad(nh, "replay", &replay);
  ASSERT_TRUE(s2.ok()) << s2.message();
  ASSERT_GT(live.numBlocks(), 20u);
  ASSERT_EQ(live.numBlocks(), replay.numBlocks());
  size_t differing = 0;
  for (const auto& b : live.blocks()) {
    const TsdfBlock* other = replay.block(b->index);
    ASSERT_NE(other, nullptr);
    differing += std::memcmp(b->voxels.data(), other->voxels.data(), sizeof(b->voxels)) != 0 ? 1 : 0;
  }
  EXPECT_EQ(differing, 0u) << "blocks differ between the live and the replayed map";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_tsdf_mapper_replay");
  std::system(("mkdir -p " + kDir).c_str());
  return RUN_ALL_TESTS();
}
