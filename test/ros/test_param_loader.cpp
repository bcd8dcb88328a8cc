// Parameter loading against a real parameter server: defaults, typed values,
// bad values and misspelt keys are refused with a message naming the key.
#include <gtest/gtest.h>

#include <tuple>

#include <ros/ros.h>

#include "surface_nbv/ros/extractor_params.h"
#include "surface_nbv/ros/mapper_params.h"
#include "surface_nbv/ros/mpc_tracker_server.h"
#include "surface_nbv/ros/planner_params.h"
#include "surface_nbv/ros/scripted_flight_server.h"
#include "surface_nbv/ros/sim_params.h"

using namespace surface_nbv;

namespace {

int counter = 0;

// A fresh private namespace and shared namespace for each case.
struct Namespaces {
  std::string priv, shared;
  Namespaces() {
    const std::string n = std::to_string(counter++);
    priv = "/case" + n + "/depth_sim";
    shared = "/case" + n + "/nbv";
    ros::param::set(priv + "/shared_namespace", shared);
  }
};

Status load(const Namespaces& ns, CameraConfig* camera, DepthSimConfig* config) {
  return loadDepthSimParams(ros::NodeHandle(ns.priv), camera, config);
}

}  // namespace

TEST(ParamLoader, DefaultsWhenNothingIsSet) {
  Namespaces ns;
  CameraConfig camera;
  DepthSimConfig config;
  ASSERT_TRUE(load(ns, &camera, &config).ok());
  EXPECT_EQ(camera.width, 640);
  EXPECT_EQ(config.scene.scene, "plant");
  EXPECT_EQ(config.world_frame, "world");
}

TEST(ParamLoader, ReadsSharedCameraAndPrivateScene) {
  Namespaces ns;
  ros::param::set(ns.shared + "/camera/width", 320);
  ros::param::set(ns.shared + "/camera/max_range", 5);  // an int where a double is expected is fine
  ros::param::set(ns.priv + "/scene", std::string("statue"));
  ros::param::set(ns.priv + "/scene_scale", 0.5);
  std::vector<double> crop_max = {1e9, 1e9, 15.0};
  ros::param::set(ns.priv + "/crop_max", crop_max);
  ros::param::set(ns.priv + "/scene_up_axis", std::string("y"));
  CameraConfig camera;
  DepthSimConfig config;
  const Status s = load(ns, &camera, &config);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(camera.width, 320);
  EXPECT_DOUBLE_EQ(camera.max_range, 5.0);
  EXPECT_EQ(config.scene.scene, "statue");
  EXPECT_DOUBLE_EQ(config.scene.transform.scale, 0.5);
  EXPECT_DOUBLE_EQ(config.scene.transform.crop.max.z(), 15.0);
  EXPECT_EQ(config.scene.transform.up_axis, "y");
}

TEST(ParamLoader, ReadsTheScenesFit) {
  Namespaces ns;
  std::vector<double> fit = {20.0, 20.0, 60.0};
  ros::param::set(ns.priv + "/scene_fit_size", fit);
  CameraConfig camera;
  DepthSimConfig config;
  const Status s = load(ns, &camera, &config);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_EQ(config.scene.transform.fit_size, Eigen::Vector3d(20, 20, 60));
}

TEST(ParamLoader, BadValuesNameTheKey) {
  struct Case {
    std::string key;
    XmlRpc::XmlRpcValue value;
    std::string expect;
  };
  std::vector<Case> cases = {
      {"shared:camera/hfov_deg", XmlRpc::XmlRpcValue(190.0), "camera/hfov_deg"},
      {"shared:camera/width", XmlRpc::XmlRpcValue(std::string("wide")), "camera/width"},
      {"shared:camera/min_range", XmlRpc::XmlRpcValue(9.0), "camera/max_range"},
      {"priv:render_threads", XmlRpc::XmlRpcValue(0), "render_threads"},
      {"priv:scene_scale", XmlRpc::XmlRpcValue(-1.0), "scale"},
      {"priv:tf_timeout", XmlRpc::XmlRpcValue(true), "tf_timeout"},
      {"priv:camera_frame", XmlRpc::XmlRpcValue(std::string("world")), "camera_frame"},
      {"priv:scene_offset", XmlRpc::XmlRpcValue(1.0), "scene_offset"},
      {"priv:scene_up_axis", XmlRpc::XmlRpcValue(std::string("x")), "up_axis"},
      {"priv:scene_fit_size", XmlRpc::XmlRpcValue(20.0), "scene_fit_size"},
  };
  for (const Case& c : cases) {
    Namespaces ns;
    const bool shared = c.key.rfind("shared:", 0) == 0;
    const std::string key = c.key.substr(c.key.find(':') + 1);
    ros::param::set((shared ? ns.shared : ns.priv) + "/" + key, c.value);
    CameraConfig camera;
    DepthSimConfig config;
    const Status s = load(ns, &camera, &config);
    EXPECT_FALSE(s.ok()) << c.key;
    EXPECT_NE(s.message().find(c.expect), std::string::npos) << c.key << ": " << s.message();
  }
}

TEST(ParamLoader, MisspeltKeysAreRefused) {
  Namespaces ns;
  ros::param::set(ns.priv + "/render_thread", 2);
  CameraConfig camera;
  DepthSimConfig config;
  Status s = load(ns, &camera, &config);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("render_thread "), std::string::npos) << s.message();

  Namespaces ns2;
  ros::param::set(ns2.shared + "/camera/hfov", 90.0);
  ros::param::set(ns2.shared + "/voxel_size", 0.3);  // shared keys of other nodes are fine
  s = load(ns2, &camera, &config);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("camera/hfov "), std::string::npos) << s.message();
}

TEST(ParamLoader, ScriptedFlightParams) {
  const std::string ns = "/flight_case";
  std::vector<double> lo = {-1, -1, 0}, hi = {1, 1, 4}, alts = {1.0, 2.0};
  ros::param::set(ns + "/target_min", lo);
  ros::param::set(ns + "/target_max", hi);
  ros::param::set(ns + "/altitudes", alts);
  ScriptedFlightNodeConfig config;
  ASSERT_TRUE(loadScriptedFlightParams(ros::NodeHandle(ns), &config).ok());
  EXPECT_EQ(config.flight.altitudes.size(), 2u);
  ros::param::set(ns + "/speed", -1.0);
  const Status s = loadScriptedFlightParams(ros::NodeHandle(ns), &config);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("speed"), std::string::npos);
  // target_max missing: the box stays empty and the node refuses to start.
  ros::param::set("/flight_case2/target_min", lo);
  ScriptedFlightNodeConfig fresh;
  EXPECT_FALSE(loadScriptedFlightParams(ros::NodeHandle("/flight_case2"), &fresh).ok());
}

TEST(ParamLoader, MapperReadsSharedMapSettings) {
  const std::string priv = "/mapper_case/tsdf_mapper", shared = "/mapper_case/nbv";
  ros::param::set(priv + "/shared_namespace", shared);
  ros::param::set(shared + "/voxel_size", 0.15);
  ros::param::set(shared + "/w_th", 0.3);
  std::vector<double> lo = {-14, -14, 0}, hi = {14, 14, 64};
  ros::param::set(shared + "/bounds_min", lo);
  ros::param::set(shared + "/bounds_max", hi);
  ros::param::set(shared + "/camera/max_range", 5.0);
  ros::param::set(shared + "/delta_pose", 3.6);  // another node's shared key: fine
  ros::param::set(priv + "/invalid_pixels", std::string("clear"));
  MapperConfig config;
  const Status s = loadMapperParams(ros::NodeHandle(priv), &config);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_DOUBLE_EQ(config.tsdf.voxel_size, 0.15);
  EXPECT_DOUBLE_EQ(config.tsdf.bounds.max.z(), 64.0);
  EXPECT_DOUBLE_EQ(config.camera.max_range, 5.0);
  EXPECT_EQ(config.tsdf.invalid_pixels, InvalidPixelPolicy::kClearToMaxRange);
}

TEST(ParamLoader, MapperTakesTheSharedTruncationUnlessItsOwnIsSet) {
  const std::string shared = "/trunc_case/nbv";
  ros::param::set(shared + "/voxel_size", 0.3);
  ros::param::set(shared + "/truncation", 0.6);
  ros::param::set("/trunc_case/a/shared_namespace", shared);
  ros::param::set("/trunc_case/b/shared_namespace", shared);
  ros::param::set("/trunc_case/b/truncation", 0.45);
  MapperConfig a, b;
  Status s = loadMapperParams(ros::NodeHandle("/trunc_case/a"), &a);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_DOUBLE_EQ(a.tsdf.truncationDistance(), 0.6);
  s = loadMapperParams(ros::NodeHandle("/trunc_case/b"), &b);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_DOUBLE_EQ(b.tsdf.truncationDistance(), 0.45);
}

TEST(ParamLoader, MapperRefusesBadValues) {
  struct Case {
    std::string key;
    XmlRpc::XmlRpcValue value;
    std::string expect;
  };
  std::vector<Case> cases = {
      {"priv:invalid_pixels", XmlRpc::XmlRpcValue(std::string("carve")), "invalid_pixels"},
      {"priv:input", XmlRpc::XmlRpcValue(std::string("laser")), "input"},
      {"priv:update_rate", XmlRpc::XmlRpcValue(0.0), "update_rate"},
      {"priv:max_blocks", XmlRpc::XmlRpcValue(0), "max_blocks"},
      {"priv:trunc", XmlRpc::XmlRpcValue(0.3), "trunc "},
      {"shared:voxel_size", XmlRpc::XmlRpcValue(-0.3), "voxel_size"},
      {"shared:truncation", XmlRpc::XmlRpcValue(0.01), "truncation"},
      {"priv:truncation", XmlRpc::XmlRpcValue(std::string("thin")), "truncation"},
      {"shared:bounds_min", XmlRpc::XmlRpcValue(3.0), "bounds_min"},
  };
  int n = 0;
  for (const Case& c : cases) {
    const std::string base = "/mapper_bad" + std::to_string(n++);
    ros::param::set(base + "/tsdf_mapper/shared_namespace", base + "/nbv");
    const bool shared = c.key.rfind("shared:", 0) == 0;
    const std::string key = c.key.substr(c.key.find(':') + 1);
    ros::param::set((shared ? base + "/nbv/" : base + "/tsdf_mapper/") + key, c.value);
    MapperConfig config;
    const Status s = loadMapperParams(ros::NodeHandle(base + "/tsdf_mapper"), &config);
    EXPECT_FALSE(s.ok()) << c.key;
    EXPECT_NE(s.message().find(c.expect), std::string::npos) << c.key << ": " << s.message();
  }
}

// nbv_planner's parameters under `base` (its shared and mission sections there too).
static Status loadPlanner(const std::string& base, PlannerNodeConfig* config) {
  ros::param::set(base + "/nbv_planner/shared_namespace", base + "/nbv");
  ros::param::set(base + "/nbv_planner/mission_namespace", base + "/mission");
  return loadPlannerParams(ros::NodeHandle(base + "/nbv_planner"), config);
}

// ise_extractor's parameters under `base`, the same way.
static Status loadExtractor(const std::string& base, ExtractorConfig* config) {
  ros::param::set(base + "/ise_extractor/shared_namespace", base + "/nbv");
  ros::param::set(base + "/ise_extractor/mission_namespace", base + "/mission");
  return loadExtractorParams(ros::NodeHandle(base + "/ise_extractor"), config);
}

// The legs' timing (speed, yaw rate) comes from the mission section, as
// nbv_mission's does, and the node's own parameters win.
TEST(ParamLoader, PlannerTimesLegsWithTheMissionSpeedAndYawRate) {
  PlannerNodeConfig config;
  ASSERT_TRUE(loadPlanner("/timing0", &config).ok());
  EXPECT_DOUBLE_EQ(config.speed, 0.5);
  ros::param::set("/timing1/mission/speed", 0.7);
  ros::param::set("/timing1/mission/yaw_rate", 0.8);
  config = PlannerNodeConfig();
  Status s = loadPlanner("/timing1", &config);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_DOUBLE_EQ(config.speed, 0.7);
  EXPECT_DOUBLE_EQ(config.yaw_rate, 0.8);
  ros::param::set("/timing2/mission/speed", 0.7);
  ros::param::set("/timing2/nbv_planner/speed", 0.3);
  config = PlannerNodeConfig();
  s = loadPlanner("/timing2", &config);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_DOUBLE_EQ(config.speed, 0.3);
  // Faster than the simulated UAV's limits (the config's tracker section): refused.
  ros::param::set("/timing3/nbv_planner/tracker_namespace", std::string("/timing3/tracker"));
  ros::param::set("/timing3/tracker/yaw_rate_max", 1.0);
  ros::param::set("/timing3/mission/yaw_rate", 2.0);
  config = PlannerNodeConfig();
  s = loadPlanner("/timing3", &config);
  // The mission section's check (nbv_mission's) names it first.
  EXPECT_NE(s.message().find("yaw_rate expected <= "), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("tracker/yaw_rate_max"), std::string::npos) << s.message();
  ros::param::set("/timing3/tracker/yaw_rate_max", 2.0);
  ros::param::set("/timing3/tracker/v_max", 0.4);
  config = PlannerNodeConfig();
  s = loadPlanner("/timing3", &config);
  EXPECT_NE(s.message().find("speed expected <= "), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("tracker/v_max"), std::string::npos) << s.message();
  ros::param::set("/timing3/tracker/v_max", 1.0);
  config = PlannerNodeConfig();
  s = loadPlanner("/timing3", &config);
  EXPECT_TRUE(s.ok()) << s.message();
}

// The tour objective comes from the YAML's mission section like the other
// explorer keys, a private parameter overrides it, and an unknown one stops
// the node naming the key.
TEST(ParamLoader, PlannerReadsTheTourObjectiveAndRefusesAnUnknownOne) {
  PlannerNodeConfig config;
  ASSERT_TRUE(loadPlanner("/objective0", &config).ok());
  EXPECT_EQ(config.explorer.graph.objective, TourObjective::kProduct);

  ros::param::set("/objective1/mission/tour_objective", std::string("sum"));
  config = PlannerNodeConfig();
  const Status sum = loadPlanner("/objective1", &config);
  ASSERT_TRUE(sum.ok()) << sum.message();
  EXPECT_EQ(config.explorer.graph.objective, TourObjective::kSum);

  ros::param::set("/objective2/mission/tour_objective", std::string("sum"));
  ros::param::set("/objective2/nbv_planner/tour_objective", std::string("product"));
  config = PlannerNodeConfig();
  ASSERT_TRUE(loadPlanner("/objective2", &config).ok());
  EXPECT_EQ(config.explorer.graph.objective, TourObjective::kProduct);

  ros::param::set("/objective3/mission/tour_objective", std::string("total"));
  config = PlannerNodeConfig();
  const Status bad = loadPlanner("/objective3", &config);
  EXPECT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("/objective3/mission/tour_objective expected 'product' or 'sum'"), std::string::npos)
      << bad.message();
}

// A planner setting in three layers: the node's default, the mission
// section's key over it, the node's private key over both. A negative value
// stops the node with a message naming the key.
struct LayeredKey {
  const char* mission_key;
  const char* node_key;
  double node_default, mission_value, node_value;
  double (*read)(const PlannerNodeConfig&);
};

static void expectLayered(const std::string& base, const LayeredKey& k) {
  SCOPED_TRACE(k.node_key);
  PlannerNodeConfig config;
  ASSERT_TRUE(loadPlanner(base + "0", &config).ok());
  EXPECT_EQ(k.read(config), k.node_default);

  ros::param::set(base + "1/mission/" + k.mission_key, k.mission_value);
  config = PlannerNodeConfig();
  ASSERT_TRUE(loadPlanner(base + "1", &config).ok());
  EXPECT_EQ(k.read(config), k.mission_value);

  ros::param::set(base + "2/mission/" + k.mission_key, k.mission_value);
  ros::param::set(base + "2/nbv_planner/" + k.node_key, k.node_value);
  config = PlannerNodeConfig();
  ASSERT_TRUE(loadPlanner(base + "2", &config).ok());
  EXPECT_EQ(k.read(config), k.node_value);

  ros::param::set(base + "3/nbv_planner/" + k.node_key, -1.0);
  config = PlannerNodeConfig();
  const Status bad = loadPlanner(base + "3", &config);
  EXPECT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find(std::string(k.node_key) + " expected >= 0"), std::string::npos) << bad.message();
}

// The node caps a decision's leg attempts at 5 wall seconds (nbv_mission: no
// cap); 0 turns the cap off.
TEST(ParamLoader, PlannerCapsLegAttemptsByDefaultAndRefusesANegativeBudget) {
  EXPECT_EQ(ExplorerConfig().leg_time_budget, 0.0);
  expectLayered("/legbudget", {"leg_time_budget", "leg_time_budget", 5.0, 2.5, 0.0,
                               [](const PlannerNodeConfig& c) { return c.explorer.leg_time_budget; }});
}

// The lattice fallback: on at 0.3 m in the node (off in nbv_mission); 0 turns
// it off.
TEST(ParamLoader, PlannerLatticeStepComesFromTheMissionUnlessItsOwnIsSet) {
  EXPECT_EQ(PathPlannerConfig().lattice_step, 0.0);
  expectLayered("/lattice", {"path_lattice_step", "lattice_step", 0.3, 0.0, 0.5,
                             [](const PlannerNodeConfig& c) { return c.path.lattice_step; }});
}

TEST(ParamLoader, MapFeedAndLegTrackingKeysAreReadAndBadOnesAreRefused) {
  PlannerNodeConfig config;
  ASSERT_TRUE(loadPlanner("/feed0", &config).ok());
  EXPECT_EQ(config.feed.update_queue, 100);
  EXPECT_EQ(config.feed.snapshot_retry, 2.0);
  EXPECT_EQ(config.leg_restart_reach, 3.0);
  EXPECT_EQ(config.max_tracking_error, 3.0);
  ros::param::set("/feed1/nbv_planner/update_queue", 7);
  ros::param::set("/feed1/nbv_planner/snapshot_retry", 0.5);
  ros::param::set("/feed1/nbv_planner/leg_restart_reach", 0.0);
  config = PlannerNodeConfig();
  ASSERT_TRUE(loadPlanner("/feed1", &config).ok());
  EXPECT_EQ(config.feed.update_queue, 7);
  EXPECT_EQ(config.feed.snapshot_retry, 0.5);
  EXPECT_EQ(config.leg_restart_reach, 0.0);
  for (const auto& [key, value, expected] :
       {std::make_tuple("update_queue", 0.0, "update_queue expected in [1, 10000]"),
        std::make_tuple("snapshot_retry", 0.0, "snapshot_retry expected > 0"),
        std::make_tuple("leg_restart_reach", -1.0, "leg_restart_reach expected in [0, 50]"),
        std::make_tuple("max_tracking_error", -1.0, "max_tracking_error expected >= 0"),
        std::make_tuple("off_track_time", 0.0, "off_track_time expected > 0")}) {
    const std::string base = std::string("/feedbad_") + key;
    if (std::string(key) == "update_queue") {
      ros::param::set(base + "/nbv_planner/" + key, static_cast<int>(value));
    } else {
      ros::param::set(base + "/nbv_planner/" + key, value);
    }
    config = PlannerNodeConfig();
    const Status bad = loadPlanner(base, &config);
    EXPECT_NE(bad.message().find(expected), std::string::npos) << key << ": " << bad.message();
  }

  ros::param::set("/feed2/nbv/voxel_size", 0.25);
  ros::param::set("/feed2/ise_extractor/update_queue", 12);
  ExtractorConfig extractor;
  ASSERT_TRUE(loadExtractor("/feed2", &extractor).ok());
  EXPECT_EQ(extractor.feed.update_queue, 12);
}

TEST(ParamLoader, ExtractorTakesTheMissionFrontierPeriodUnlessItsOwnIsSet) {
  const auto load = [](const std::string& base, ExtractorConfig* c) {
    *c = ExtractorConfig();
    return loadExtractor(base, c);
  };
  ExtractorConfig c;
  ASSERT_TRUE(load("/period0", &c).ok());
  EXPECT_EQ(c.frontier_period, 0.0);  // no mission section: rate per wall second
  EXPECT_EQ(c.rate, 1.0);
  ros::param::set("/period1/mission/frontier_period", 2.5);
  ASSERT_TRUE(load("/period1", &c).ok());
  EXPECT_EQ(c.frontier_period, 2.5);
  ros::param::set("/period2/mission/frontier_period", 2.5);
  ros::param::set("/period2/ise_extractor/frontier_period", 0.0);
  ASSERT_TRUE(load("/period2", &c).ok());
  EXPECT_EQ(c.frontier_period, 0.0);
  ros::param::set("/period3/ise_extractor/frontier_period", -1.0);
  Status bad = load("/period3", &c);
  EXPECT_NE(bad.message().find("frontier_period expected >= 0"), std::string::npos) << bad.message();
  ros::param::set("/period4/mission/frontier_period", std::string("two"));
  bad = load("/period4", &c);
  EXPECT_FALSE(bad.ok());
  EXPECT_NE(bad.message().find("frontier_period"), std::string::npos) << bad.message();
}

// mpc_tracker: the UAV's limits from the config's tracker section (shared
// with nbv_mission), the node's own values over them, misspelt keys refused.
TEST(ParamLoader, TrackerLimitsFromTheTrackerSectionThenThePrivateOnes) {
  const std::string n = std::to_string(counter++);
  const std::string priv = "/case" + n + "/mpc_tracker", shared = "/case" + n + "/tracker";
  ros::param::set(priv + "/tracker_namespace", shared);
  ros::param::set(shared + "/yaw_rate_max", 2.0);
  ros::param::set(shared + "/v_max", 0.8);
  ros::param::set(priv + "/v_max", 0.6);
  TrackerNodeConfig c;
  Status s = loadTrackerParams(ros::NodeHandle(priv), &c);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_DOUBLE_EQ(c.sim.model.yaw_rate_max, 2.0);
  EXPECT_DOUBLE_EQ(c.sim.model.v_max, 0.6);
  ros::param::set(shared + "/yaw_rate", 2.0);
  c = TrackerNodeConfig();
  s = loadTrackerParams(ros::NodeHandle(priv), &c);
  EXPECT_NE(s.message().find(shared + "/yaw_rate is not a parameter"), std::string::npos) << s.message();
  ros::param::del(shared + "/yaw_rate");
  ros::param::set(shared + "/a_max", -1.0);
  c = TrackerNodeConfig();
  s = loadTrackerParams(ros::NodeHandle(priv), &c);
  EXPECT_NE(s.message().find("a_max"), std::string::npos) << s.message();
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_param_loader");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
