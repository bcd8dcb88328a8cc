#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "surface_nbv/eval/eval_config.h"

namespace surface_nbv {
namespace {

TEST(EvalConfig, DefaultsValidateAndResolveFromTheVoxelSize) {
  EvalConfig c;
  ASSERT_TRUE(c.validate()) << c.validate().message();
  EXPECT_DOUBLE_EQ(c.eMax(), 0.3 * std::sqrt(3.0) / 2.0);
  EXPECT_NEAR(c.eMax(), 0.2598, 1e-4);  // Table 2: 25.98 cm at rho_v = 0.3 m
  EXPECT_DOUBLE_EQ(c.spacing(), 0.1);
  EXPECT_DOUBLE_EQ(c.projectionRadius(), 0.15);
  EXPECT_DOUBLE_EQ(c.maxDepth(), c.eMax());
  c.point_spacing = 0.05;
  c.projection_radius = 0.2;
  c.max_depth = 0.4;
  EXPECT_DOUBLE_EQ(c.spacing(), 0.05);
  EXPECT_DOUBLE_EQ(c.projectionRadius(), 0.2);
  EXPECT_DOUBLE_EQ(c.maxDepth(), 0.4);
}

TEST(EvalConfig, AutomaticBoundsGrowAroundTheGroundTruthButNotBelow) {
  EvalConfig c;
  c.bounds_margin = 2.0;
  const AlignedBox b = c.sensorBounds(AlignedBox(Eigen::Vector3d(-1, -2, 0.5), Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(b.min.isApprox(Eigen::Vector3d(-3, -4, 0.5)));
  EXPECT_TRUE(b.max.isApprox(Eigen::Vector3d(3, 4, 5)));
  c.bounds = AlignedBox(Eigen::Vector3d(-9, -9, -1), Eigen::Vector3d(9, 9, 9));
  EXPECT_TRUE(c.sensorBounds(b).min.isApprox(Eigen::Vector3d(-9, -9, -1)));
}

TEST(EvalConfig, ValidateNamesTheBadKey) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(EvalConfig&)>>> cases = {
      {"voxel_size", [](EvalConfig& c) { c.voxel_size = 0.0; }},
      {"voxel_size", [nan](EvalConfig& c) { c.voxel_size = nan; }},
      {"point_spacing", [](EvalConfig& c) { c.point_spacing = -0.1; }},
      {"max_points", [](EvalConfig& c) { c.max_points = 0; }},
      {"threads", [](EvalConfig& c) { c.threads = 0; }},
      {"bounds", [](EvalConfig& c) { c.bounds = AlignedBox(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 0)); }},
      {"bounds_margin", [](EvalConfig& c) { c.bounds_margin = -1.0; }},
      {"min_range", [](EvalConfig& c) { c.min_range = -1.0; }},
      {"max_range", [](EvalConfig& c) { c.max_range = 1.0; }},
      {"collision_radius", [nan](EvalConfig& c) { c.collision_radius = nan; }},
      {"free_space_cell", [](EvalConfig& c) { c.free_space_cell = 0.0; }},
      {"max_incidence_deg", [](EvalConfig& c) { c.max_incidence_deg = 90.0; }},
      {"visibility_rays", [](EvalConfig& c) { c.visibility_rays = 0; }},
      {"projection_radius", [](EvalConfig& c) { c.projection_radius = -0.1; }},
      {"max_depth", [](EvalConfig& c) { c.max_depth = -0.1; }},
      {"normal_radius", [](EvalConfig& c) { c.normal_radius = -0.1; }},
      {"normal_agreement_deg", [](EvalConfig& c) { c.normal_agreement_deg = 0.0; }},
      {"min_neighbours", [](EvalConfig& c) { c.min_neighbours = 0; }},
  };
  for (const auto& [key, spoil] : cases) {
    EvalConfig c;
    spoil(c);
    const Status s = c.validate();
    EXPECT_FALSE(s) << key;
    EXPECT_EQ(s.message().rfind(key + " expected", 0), 0u) << "'" << s.message() << "' should name " << key;
  }
}

}  // namespace
}  // namespace surface_nbv
