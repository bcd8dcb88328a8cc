// The ROS nodes and nbv_mission read one config file alike (issue #41): each
// shipped config/*.yaml is loaded by loadMissionConfig (the file) and, put
// on the parameter server as the launch loads it, by the nodes' loaders
// (loadMissionParams, loadPlannerParams, loadMapperParams,
// loadExtractorParams, loadTrackerParams); both give the same values and
// both refuse the same bad variants, with the same key named.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <yaml-cpp/yaml.h>

#include "surface_nbv/mission/mission_config.h"
#include "surface_nbv/ros/extractor_params.h"
#include "surface_nbv/ros/mapper_params.h"
#include "surface_nbv/ros/mission_params.h"
#include "surface_nbv/ros/mpc_tracker_server.h"
#include "surface_nbv/ros/planner_params.h"

using namespace surface_nbv;

namespace {

XmlRpc::XmlRpcValue toXmlRpc(const YAML::Node& n) {
  XmlRpc::XmlRpcValue v;
  if (n.IsMap()) {
    for (const auto& kv : n) v[kv.first.as<std::string>()] = toXmlRpc(kv.second);
  } else if (n.IsSequence()) {
    v.setSize(static_cast<int>(n.size()));
    for (size_t i = 0; i < n.size(); ++i) v[static_cast<int>(i)] = toXmlRpc(n[i]);
  } else if (n.IsScalar()) {
    const std::string s = n.Scalar();
    // As rosparam types a scalar: bool, int, double, else string.
    bool b;
    int i;
    double d;
    if (n.Tag() != "!" && YAML::convert<bool>::decode(n, b) && (s == "true" || s == "false")) {
      v = b;
    } else if (n.Tag() != "!" && YAML::convert<int>::decode(n, i) && s.find_first_of(".eE") == std::string::npos) {
      v = i;
    } else if (n.Tag() != "!" && YAML::convert<double>::decode(n, d)) {
      v = d;
    } else {
      v = s;
    }
  }
  return v;
}

const char* const kSections[] = {"nbv", "depth_sim", "tracker", "mission"};

// The document on the parameter server, as `rosparam load` puts it.
void loadOnServer(const YAML::Node& root) {
  for (const char* s : kSections) ros::param::del(std::string("/") + s);
  for (const char* s : kSections) {
    if (root[s] && root[s].IsMap()) ros::param::set(std::string("/") + s, toXmlRpc(root[s]));
  }
}

std::vector<std::string> shippedConfigs() {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(std::string(NBV_SOURCE_DIR) + "/config")) {
    if (e.path().extension() == ".yaml") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

struct NodeLoads {
  Status mission, planner, mapper, extractor, tracker;
  MissionConfig m;
  PlannerNodeConfig planner_config;
  MapperConfig mapper_config;
  ExtractorConfig extractor_config;
  TrackerNodeConfig tracker_config;
};

NodeLoads loadThroughNodes() {
  NodeLoads r;
  ros::NodeHandle priv("~");
  r.mission = loadMissionParams("/nbv", "/mission", kTrackerNamespace, &r.m);
  r.planner = loadPlannerParams(priv, &r.planner_config);
  r.mapper = loadMapperParams(priv, &r.mapper_config);
  r.extractor = loadExtractorParams(priv, &r.extractor_config);
  r.tracker = loadTrackerParams(priv, &r.tracker_config);
  return r;
}

void expectSameExplorer(const ExplorerConfig& a, const ExplorerConfig& b, const std::string& what) {
  EXPECT_EQ(a.travel_yaw, b.travel_yaw) << what;
  EXPECT_EQ(a.head_lookahead, b.head_lookahead) << what;
  EXPECT_EQ(a.head_unknown, b.head_unknown) << what;
  EXPECT_DOUBLE_EQ(a.head_vertical_scale, b.head_vertical_scale) << what;
  EXPECT_EQ(a.min_visible, b.min_visible) << what;
  EXPECT_DOUBLE_EQ(a.pool_unknown_below, b.pool_unknown_below) << what;
  EXPECT_EQ(a.check_reachable, b.check_reachable) << what;
  EXPECT_EQ(a.corridor_guide, b.corridor_guide) << what;
  EXPECT_DOUBLE_EQ(a.turn_distance, b.turn_distance) << what;
  EXPECT_EQ(a.max_visits, b.max_visits) << what;
  EXPECT_EQ(a.gaze.enabled, b.gaze.enabled) << what;
  EXPECT_DOUBLE_EQ(a.graph.lambda_tc, b.graph.lambda_tc) << what;
  EXPECT_DOUBLE_EQ(a.graph.lambda_ic, b.graph.lambda_ic) << what;
  EXPECT_EQ(a.graph.objective, b.graph.objective) << what;
}

TEST(ConfigParity, EveryShippedConfigReadsTheSameThroughBothLoaders) {
  const std::vector<std::string> files = shippedConfigs();
  ASSERT_GE(files.size(), 5u);
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    MissionConfig yaml;
    ASSERT_TRUE(loadMissionConfig(file, &yaml).ok()) << loadMissionConfig(file, &yaml).message();
    ASSERT_TRUE(yaml.validate().ok()) << yaml.validate().message();
    const YAML::Node root = YAML::LoadFile(file);
    // Without a mission section (room, sphere) the nodes keep their own
    // defaults for the flight-time limit (none), the take-off ball (none)
    // and the frontier period (per wall second): a stack of one's own
    // flies no mission of nbv_mission's.
    const bool mission = root["mission"] && root["mission"].IsMap() && root["mission"].size() > 0;
    loadOnServer(root);
    const NodeLoads ros = loadThroughNodes();
    ASSERT_TRUE(ros.mission.ok()) << ros.mission.message();
    ASSERT_TRUE(ros.planner.ok()) << ros.planner.message();
    ASSERT_TRUE(ros.mapper.ok()) << ros.mapper.message();
    ASSERT_TRUE(ros.extractor.ok()) << ros.extractor.message();
    ASSERT_TRUE(ros.tracker.ok()) << ros.tracker.message();
    // The whole mission config, as nbv_mission has it.
    EXPECT_DOUBLE_EQ(ros.m.tsdf.voxel_size, yaml.tsdf.voxel_size);
    EXPECT_TRUE(ros.m.tsdf.bounds.min.isApprox(yaml.tsdf.bounds.min));
    EXPECT_TRUE(ros.m.tsdf.bounds.max.isApprox(yaml.tsdf.bounds.max));
    EXPECT_DOUBLE_EQ(ros.m.camera.max_range, yaml.camera.max_range);
    EXPECT_DOUBLE_EQ(ros.m.camera.pitch_deg, yaml.camera.pitch_deg);
    EXPECT_TRUE(ros.m.start.isApprox(yaml.start));
    EXPECT_DOUBLE_EQ(ros.m.frontier_period, yaml.frontier_period);
    EXPECT_DOUBLE_EQ(ros.m.max_flight_time, yaml.max_flight_time);
    expectSameExplorer(ros.m.explorer, yaml.explorer, "mission config");
    // Each node's part of it.
    const PlannerNodeConfig& p = ros.planner_config;
    expectSameExplorer(p.explorer, yaml.explorer, "nbv_planner");
    EXPECT_DOUBLE_EQ(p.speed, yaml.speed);
    EXPECT_DOUBLE_EQ(p.yaw_rate, yaml.yaw_rate);
    EXPECT_DOUBLE_EQ(p.leg_lookahead, yaml.leg_lookahead);
    EXPECT_DOUBLE_EQ(p.leg_yaw_tolerance, yaml.leg_yaw_tolerance);
    if (mission) {
      EXPECT_DOUBLE_EQ(p.max_flight_time, yaml.max_flight_time);
    }
    EXPECT_DOUBLE_EQ(p.start_spin, yaml.start_spin);
    // The mission's rules: the same flight keys and reach, the drivers'
    // own ways of seeing a leg end and a frontier come (mission_supervisor.h).
    const SupervisorConfig node_rules = p.supervisorConfig(), mission_rules = yaml.supervisorConfig();
    EXPECT_DOUBLE_EQ(node_rules.flight.speed, mission_rules.flight.speed);
    EXPECT_DOUBLE_EQ(node_rules.flight.leg_lookahead, mission_rules.flight.leg_lookahead);
    EXPECT_DOUBLE_EQ(node_rules.flight.start_spin, mission_rules.flight.start_spin);
    if (mission) {
      EXPECT_DOUBLE_EQ(node_rules.flight.max_flight_time, mission_rules.flight.max_flight_time);
    }
    EXPECT_DOUBLE_EQ(node_rules.reach_tolerance, mission_rules.reach_tolerance);
    EXPECT_DOUBLE_EQ(node_rules.frontier_period, 0.0);
    EXPECT_DOUBLE_EQ(mission_rules.frontier_period, yaml.frontier_period);
    EXPECT_EQ(p.path.iteration_budget, yaml.path.iteration_budget);
    EXPECT_DOUBLE_EQ(p.path.time_budget, yaml.path.time_budget);
    EXPECT_DOUBLE_EQ(p.map.voxel_size, yaml.tsdf.voxel_size);
    EXPECT_DOUBLE_EQ(ros.mapper_config.tsdf.voxel_size, yaml.tsdf.voxel_size);
    EXPECT_DOUBLE_EQ(ros.mapper_config.tsdf.mesh_voxel_size, yaml.tsdf.mesh_voxel_size);
    EXPECT_EQ(ros.mapper_config.tsdf.mesh_weight_dropoff, yaml.tsdf.mesh_weight_dropoff);
    EXPECT_DOUBLE_EQ(ros.mapper_config.camera.min_range, yaml.camera.min_range);
    if (mission) {
      EXPECT_DOUBLE_EQ(ros.mapper_config.start_free_radius, yaml.start_free_radius);
    }
    const SurfaceConfig& s = ros.extractor_config.surface;
    EXPECT_DOUBLE_EQ(s.delta_pose, yaml.surface.delta_pose);
    EXPECT_DOUBLE_EQ(s.d_nu, yaml.surface.d_nu);
    EXPECT_DOUBLE_EQ(s.approach_range_fraction, yaml.surface.approach_range_fraction);
    if (mission) {
      EXPECT_DOUBLE_EQ(ros.extractor_config.frontier_period, yaml.frontier_period);
    }
    EXPECT_DOUBLE_EQ(ros.tracker_config.sim.model.v_max, yaml.tracker.model.v_max);
    EXPECT_DOUBLE_EQ(ros.tracker_config.sim.model.yaw_rate_max, yaml.tracker.model.yaw_rate_max);
    EXPECT_DOUBLE_EQ(ros.tracker_config.sim.model.a_max, yaml.tracker.model.a_max);
    EXPECT_DOUBLE_EQ(ros.tracker_config.sim.mpc.jerk_max, yaml.tracker.mpc.jerk_max);
  }
}

// A variant of the power plant's config: `section`/`key` set to `value`
// (YAML text), or removed with value "~remove".
struct Variant {
  std::string section, key, value;
  bool accepted;     // by both
  std::string says;  // what the refusal names (both)
};

TEST(ConfigParity, BothLoadersRefuseAndAcceptTheSameVariants) {
  const std::string base_file = std::string(NBV_SOURCE_DIR) + "/config/powerplant.yaml";
  const std::vector<Variant> variants = {
      {"mission", "speed", "0.8", true, ""},                 // within the tracker's v_max: both fly it
      {"mission", "speed", "25.0", false, "speed"},          // nbv_mission took (0, 5], the planner (0, 20]
      {"mission", "speed", "2.0", false, "v_max"},           // faster than the tracker section allows
      {"mission", "yaw_rate", "0.0", false, "yaw_rate"},
      {"mission", "max_flight_time", "0.0", true, ""},       // 0: no limit, in both now
      {"mission", "max_flight_time", "-5.0", false, "max_flight_time"},
      {"mission", "head_lambda", ".nan", false, "head_lambda"},
      {"mission", "tour_objective", "longest", false, "tour_objective"},
      {"mission", "travel_yawn", "true", false, "travel_yawn"},  // misspelt: unknown key
      {"mission", "max_visits", "two", false, "max_visits"},     // wrong type
      {"mission", "start", "[0, 0, 2]", false, "start"},
      {"tracker", "v_maxx", "2.0", false, "v_maxx"},
      {"nbv", "voxel_size", "-0.3", false, "voxel_size"},
      {"nbv", "lambda_tc", "-1.0", false, "lambda_tc"},
  };
  for (const Variant& v : variants) {
    SCOPED_TRACE(v.section + "/" + v.key + ": " + v.value);
    YAML::Node root = YAML::LoadFile(base_file);
    root[v.section][v.key] = YAML::Load(v.value);
    YAML::Emitter out;
    out << root;
    MissionConfig yaml;
    Status file = loadMissionConfigText(out.c_str(), "variant.yaml", &yaml);
    if (file) file = yaml.validate();
    loadOnServer(YAML::Load(out.c_str()));
    const NodeLoads ros = loadThroughNodes();
    EXPECT_EQ(file.ok(), v.accepted) << file.message();
    EXPECT_EQ(ros.mission.ok(), v.accepted) << ros.mission.message();
    EXPECT_EQ(ros.planner.ok(), v.accepted) << ros.planner.message();
    if (!v.accepted) {
      EXPECT_NE(file.message().find(v.says), std::string::npos) << file.message();
      EXPECT_NE(ros.planner.message().find(v.says), std::string::npos) << ros.planner.message();
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_config_parity");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
