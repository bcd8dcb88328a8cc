// The core concerns must stay ROS-free: no file under src/<concern> or
// include/surface_nbv/<concern> may include a ROS header.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kConcerns = {"sim", "map", "surface", "planning", "tracking", "eval", "util"};

std::vector<std::string> rosIncludes(const fs::path& file) {
  static const std::regex ros_include(
      R"(^\s*#\s*include\s*[<"](ros/|tf2_ros/|tf2_eigen/|tf2_msgs/|std_msgs/|std_srvs/|sensor_msgs/|geometry_msgs/|nav_msgs/|visualization_msgs/|trajectory_msgs/|rosbag/|message_filters/|surface_nbv/ros/|surface_nbv/[A-Z]\w*\.h))");
  std::vector<std::string> hits;
  std::ifstream in(file);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (std::regex_search(line, ros_include)) hits.push_back(file.string() + ":" + std::to_string(n) + ": " + line);
  }
  return hits;
}

}  // namespace

TEST(CoreIsRosFree, DetectorCatchesRosIncludes) {
  const fs::path tmp = fs::temp_directory_path() / "surface_nbv_ros_include_probe.h";
  std::ofstream(tmp) << "#include <vector>\n#include <ros/ros.h>\n  #include \"sensor_msgs/Image.h\"\n"
                        "#include \"surface_nbv/NodeStats.h\"\n#include \"surface_nbv/sensor/depth_camera.h\"\n";
  EXPECT_EQ(rosIncludes(tmp).size(), 3u);
  fs::remove(tmp);
}

TEST(CoreIsRosFree, NoCoreFileIncludesRos) {
  const fs::path root(NBV_SOURCE_DIR);
  size_t scanned = 0;
  std::vector<std::string> hits;
  for (const std::string& concern : kConcerns) {
    for (const fs::path& dir : {root / "src" / concern, root / "include" / "surface_nbv" / concern}) {
      if (!fs::exists(dir)) continue;
      for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        if (!entry.is_regular_file()) continue;
        ++scanned;
        for (const std::string& h : rosIncludes(entry.path())) hits.push_back(h);
      }
    }
  }
  EXPECT_GT(scanned, 10u) << "the scan found almost no core files: is NBV_SOURCE_DIR right?";
  for (const std::string& h : hits) ADD_FAILURE() << "ROS header in a core concern: " << h;
}
