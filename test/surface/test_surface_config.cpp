#include "surface_nbv/surface/surface_config.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

using namespace surface_nbv;

TEST(SurfaceConfig, DefaultsAreValidAndThePapersPowerplantValues) {
  const SurfaceConfig c;
  EXPECT_TRUE(c.validate().ok()) << c.validate().message();
  EXPECT_DOUBLE_EQ(c.delta_pose, 4.7);
  EXPECT_DOUBLE_EQ(c.d_nu, 2.0);
  EXPECT_DOUBLE_EQ(c.d_nu_max, 5.0);
  EXPECT_DOUBLE_EQ(c.collision_radius, 1.0);
  EXPECT_TRUE(c.unknown_blocks_visibility);
}

TEST(SurfaceConfig, EachBadValueIsNamed) {
  const std::vector<std::pair<std::string, std::function<void(SurfaceConfig*)>>> cases = {
      {"delta_pose", [](SurfaceConfig* c) { c->delta_pose = 0.0; }},
      {"delta_pose", [](SurfaceConfig* c) { c->delta_pose = 9.0; }},  // beyond the 8 m range
      {"fallback_rotations_deg", [](SurfaceConfig* c) { c->fallback_rotations_deg = {30.0, 0.0}; }},
      {"fallback_distance_fractions", [](SurfaceConfig* c) { c->fallback_distance_fractions = {1.5}; }},
      {"fov_margin_deg", [](SurfaceConfig* c) { c->fov_margin_deg = 30.0; }},
      {"collision_radius", [](SurfaceConfig* c) { c->collision_radius = -1.0; }},
      {"epsilon", [](SurfaceConfig* c) { c->epsilon = 0.0; }},
      {"parallel_distance", [](SurfaceConfig* c) { c->parallel_distance = -0.1; }},
      {"parallel_cos", [](SurfaceConfig* c) { c->parallel_cos = 1.5; }},
      {"d_nu", [](SurfaceConfig* c) { c->d_nu = std::nan(""); }},
      {"d_nu_max", [](SurfaceConfig* c) { c->d_nu_max = 1.0; }},
      {"d_nu_step", [](SurfaceConfig* c) { c->d_nu_step = 0.0; }},
      {"threads", [](SurfaceConfig* c) { c->threads = 0; }},
      {"camera/hfov_deg", [](SurfaceConfig* c) { c->camera.hfov_deg = 200.0; }},
  };
  for (const auto& [key, spoil] : cases) {
    SurfaceConfig c;
    spoil(&c);
    const Status s = c.validate();
    EXPECT_FALSE(s.ok()) << key;
    EXPECT_EQ(s.message().rfind(key + " ", 0), 0u) << "'" << s.message() << "' should name " << key;
  }
}
