// RenderAhead (mission/render_ahead.h): frames rendered on the worker at the
// poses a copy of the tracker reaches are handed over only at the same index
// and pose, equal to rendering them in line; a new trajectory gets none of
// them; planning again does not render a frame twice.
#include "surface_nbv/mission/render_ahead.h"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <thread>
#include <vector>

#include "surface_nbv/sim/procedural_scenes.h"
#include "surface_nbv/sim/scripted_flight.h"
#include "surface_nbv/tracking/trajectory.h"

using namespace surface_nbv;

namespace {

constexpr double kFrameDt = 0.2;
constexpr size_t kFrames = 12;

class RenderAheadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    TriangleMesh mesh;
    ASSERT_TRUE(makeProceduralScene("statue", &mesh).ok());
    ASSERT_TRUE(RaycastScene::create(mesh, &scene_).ok());
    CameraConfig camera;
    camera.width = 96;
    camera.height = 72;
    camera.max_range = 8.0;
    renderer_ = std::make_unique<DepthRenderer>(*scene_, DepthCamera(camera), 1);
    initial_.p_W = Eigen::Vector3d(-14.0, 0.0, 3.0);
  }

  // A leg from the start: along +y while climbing and turning towards the statue.
  static Trajectory leg(const Eigen::Vector3d& to, double yaw) {
    return timeWaypoints({{Eigen::Vector3d(-14.0, 0.0, 3.0), 0.0}, {to, yaw}}, 0.0, 1.0, 0.5);
  }

  // Steps `tracker` to frame `k` as MissionRunner does and returns the camera pose.
  Transform stepToFrame(TrackerSim* tracker, double* next_frame) const {
    while (tracker->time() + 1e-9 < *next_frame) tracker->step();
    *next_frame += kFrameDt;
    return levelBodyPose(tracker->state().p_W, tracker->state().yaw) * T_B_C_;
  }

  // Waits until the worker has rendered `n` frames (or 20 s have passed).
  static void waitRendered(const RenderAhead& ahead, uint64_t n) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (ahead.stats().rendered < n && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }

  std::unique_ptr<RaycastScene> scene_;
  std::unique_ptr<DepthRenderer> renderer_;
  UavState initial_;
  const Transform T_B_C_ = opticalInBody();
};

TEST_F(RenderAheadTest, FramesAlongAKeptTrajectoryEqualRenderingThemInLine) {
  TrackerSim tracker(TrackerSimConfig(), initial_);
  ASSERT_TRUE(tracker.setTrajectory(leg(Eigen::Vector3d(-14.0, 4.0, 5.0), 0.6)).ok());
  RenderAhead ahead(*renderer_, kFrames, T_B_C_);
  ahead.plan(tracker, 0.0, kFrameDt, 0);
  waitRendered(ahead, kFrames);
  double next_frame = 0.0;
  size_t seen = 0;
  for (uint64_t k = 0; k < kFrames; ++k) {
    const Transform T = stepToFrame(&tracker, &next_frame);
    DepthImage taken, in_line;
    ASSERT_TRUE(ahead.take(k, T, &taken)) << "frame " << k;
    renderer_->render(T, &in_line, k);
    EXPECT_TRUE(taken.data == in_line.data) << "frame " << k;  // misses are +-Inf, no NaN
    seen += taken.validCount() > 0 ? 1 : 0;
  }
  EXPECT_GT(seen, kFrames / 2);  // the frames see the statue
  // Past the plan: nothing to take.
  const Transform T = stepToFrame(&tracker, &next_frame);
  DepthImage image;
  EXPECT_FALSE(ahead.take(kFrames, T, &image));
  const RenderAheadStats stats = ahead.stats();
  EXPECT_EQ(stats.rendered, kFrames);
  EXPECT_EQ(stats.taken, kFrames);
}

TEST_F(RenderAheadTest, ANewTrajectoryTakesNoFrameOfTheOldOne) {
  TrackerSim tracker(TrackerSimConfig(), initial_);
  ASSERT_TRUE(tracker.setTrajectory(leg(Eigen::Vector3d(-14.0, 4.0, 5.0), 0.6)).ok());
  RenderAhead ahead(*renderer_, kFrames, T_B_C_);
  ahead.plan(tracker, 0.0, kFrameDt, 0);
  waitRendered(ahead, kFrames);
  double next_frame = 0.0;
  DepthImage image;
  ASSERT_TRUE(ahead.take(0, stepToFrame(&tracker, &next_frame), &image));
  // The UAV turns away: the frames rendered for the old leg do not match.
  ASSERT_TRUE(tracker.setTrajectory(timeWaypoints({{tracker.state().p_W, tracker.state().yaw},
                                                   {Eigen::Vector3d(-16.0, -3.0, 3.0), -1.5}},
                                                  tracker.time(), 1.0, 0.5))
                  .ok());
  for (uint64_t k = 1; k < kFrames; ++k) {
    EXPECT_FALSE(ahead.take(k, stepToFrame(&tracker, &next_frame), &image)) << "frame " << k;
  }
  // Only frame 0 was handed over.
  EXPECT_EQ(ahead.stats().taken, 1u);
}

TEST_F(RenderAheadTest, PlanningAgainRendersNoFrameTwice) {
  TrackerSim tracker(TrackerSimConfig(), initial_);
  ASSERT_TRUE(tracker.setTrajectory(leg(Eigen::Vector3d(-14.0, 4.0, 5.0), 0.6)).ok());
  RenderAhead ahead(*renderer_, kFrames, T_B_C_);
  ahead.plan(tracker, 0.0, kFrameDt, 0);
  ahead.plan(tracker, 0.0, kFrameDt, 0);
  waitRendered(ahead, kFrames);
  // Six frames on, the same trajectory planned again from there.
  double next_frame = 0.0;
  for (uint64_t k = 0; k < 6; ++k) {
    DepthImage image;
    ASSERT_TRUE(ahead.take(k, stepToFrame(&tracker, &next_frame), &image)) << "frame " << k;
  }
  ahead.plan(tracker, next_frame, kFrameDt, 6);
  waitRendered(ahead, kFrames + 6);
  for (uint64_t k = 6; k < kFrames + 6; ++k) {
    DepthImage image;
    ASSERT_TRUE(ahead.take(k, stepToFrame(&tracker, &next_frame), &image)) << "frame " << k;
  }
  const RenderAheadStats stats = ahead.stats();
  EXPECT_EQ(stats.plans, 3u);
  EXPECT_EQ(stats.rendered, kFrames + 6);  // frames 6-11 were not rendered again
  EXPECT_EQ(stats.taken, kFrames + 6);
}

TEST_F(RenderAheadTest, NoFramesAheadTakesNothing) {
  TrackerSim tracker(TrackerSimConfig(), initial_);
  RenderAhead ahead(*renderer_, 0, T_B_C_);
  ahead.plan(tracker, 0.0, kFrameDt, 0);
  double next_frame = 0.0;
  DepthImage image;
  EXPECT_FALSE(ahead.take(0, stepToFrame(&tracker, &next_frame), &image));
  EXPECT_EQ(ahead.stats().plans, 0u);
  EXPECT_EQ(ahead.stats().rendered, 0u);
}

// A frame the caller asks for before the worker starts it is the caller's:
// the worker skips it, and a frame it is rendering is waited for.
TEST_F(RenderAheadTest, AFrameTakenBeforeItsTurnIsSkipped) {
  TrackerSim tracker(TrackerSimConfig(), initial_);
  ASSERT_TRUE(tracker.setTrajectory(leg(Eigen::Vector3d(-14.0, 4.0, 5.0), 0.6)).ok());
  RenderAhead ahead(*renderer_, kFrames, T_B_C_);
  double next_frame = 0.0;
  TrackerSim copy = tracker;
  DepthImage image;
  // Claim frames 0-3 before any plan: none is there.
  for (uint64_t k = 0; k < 4; ++k) EXPECT_FALSE(ahead.take(k, stepToFrame(&copy, &next_frame), &image));
  ahead.plan(tracker, 0.0, kFrameDt, 0);
  waitRendered(ahead, kFrames - 4);
  for (uint64_t k = 4; k < kFrames; ++k) {
    EXPECT_TRUE(ahead.take(k, stepToFrame(&copy, &next_frame), &image)) << "frame " << k;
  }
  EXPECT_EQ(ahead.stats().rendered, kFrames - 4);
}

}  // namespace
