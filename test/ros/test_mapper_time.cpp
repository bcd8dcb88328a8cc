// Timestamps and TF against a real tsdf_mapper (mapper_time.test): the test
// owns /clock, /tf and the depth topics, and checks for each scenario the
// change of every drop counter, frames_integrated and time_resets on
// tsdf/stats, and whether the saved map changed. The node must fuse a frame
// only at the transform of its own stamp: it waits up to ~tf_wait (2 s here)
// for that transform, never extrapolates, drops and counts what cannot be
// placed, and resets its queue when the stamps jump back by more than a
// second (a bag restarted), and its TF buffer if that still holds the sensor
// poses from before the jump. Every scenario has its own camera frame name,
// so its transforms start from an empty history; stamps move forward by 10 s
// per scenario except where the scenario moves the clock.
// The scenarios run in the order written and share one mapper.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <set>

#include "mapper_probe.h"

using namespace surface_nbv;

namespace {

const std::string kDir = "/tmp/surface_nbv_mapper_time_test";
constexpr double kTfWait = 2.0;  // as mapper_time.test
MapperProbe* probe = nullptr;
int scenario_index = 0;

// The counters every scenario accounts for; a scenario lists the changes it
// expects and every other one must stay.
bool isAccounted(const std::string& name) {
  return name.rfind("dropped_", 0) == 0 || name == "frames_integrated" || name == "time_resets";
}

// One scenario: its stamp base, a camera pose of its own (so that its frames
// change voxels no other scenario touched last) and the state before it.
class Scenario {
 public:
  explicit Scenario(const std::string& name) : name_(name), index_(scenario_index++) {
    t_ = probe->clock() + 10.0;
    probe->setClock(t_);
    EXPECT_TRUE(probe->freshStats(2)) << name_ << ": no tsdf/stats";
    before_ = probe->counters();
    map_before_ = probe->digest();
    EXPECT_TRUE(map_before_.valid) << name_ << ": " << map_before_.error;
  }

  double t() const { return t_; }
  std::string frame(const std::string& suffix = "") const { return "cam_" + name_ + suffix; }
  Eigen::Vector3d pose(int k = 0) const {
    return Eigen::Vector3d(-1.5 + 0.25 * (index_ % 12) + 0.05 * k, -1.0 + 0.4 * (index_ / 12), 0.5);
  }
  uint64_t delta(const std::string& counter) const { return surface_nbv::delta(before_, probe->counters(), counter); }

  // Waits until every counter of `expected` has grown by at least its value
  // (or `timeout` passed), lets the node settle, then checks that every
  // accounted counter changed by exactly its expected value and that the map
  // changed iff `map_changes`.
  void finish(const std::map<std::string, uint64_t>& expected, bool map_changes, double timeout = 15.0) {
    const ros::WallTime start = ros::WallTime::now();
    const bool reached = MapperProbe::waitUntil(
        [&] {
          for (const auto& [counter, n] : expected) {
            if (delta(counter) < n) return false;
          }
          return true;
        },
        timeout);
    const double seconds = (ros::WallTime::now() - start).toSec();
    ros::WallDuration(0.3).sleep();
    EXPECT_TRUE(probe->freshStats(2)) << name_;
    const Counters after = probe->counters();
    EXPECT_TRUE(reached) << name_ << ": expected counters not reached in " << timeout << " s";
    std::set<std::string> names;
    for (const auto& kv : before_) names.insert(kv.first);
    for (const auto& kv : after) names.insert(kv.first);
    for (const auto& kv : expected) names.insert(kv.first);
    std::string changes;
    for (const std::string& n : names) {
      if (!isAccounted(n)) continue;
      const auto it = expected.find(n);
      const uint64_t want = it == expected.end() ? 0 : it->second;
      const uint64_t got = surface_nbv::delta(before_, after, n);
      EXPECT_EQ(got, want) << name_ << ": counter " << n;
      if (got > 0) changes += " " + n + " +" + std::to_string(got);
    }
    const MapDigest map_after = probe->digest();
    ASSERT_TRUE(map_after.valid) << name_ << ": " << map_after.error;
    if (map_changes) {
      EXPECT_NE(map_after, map_before_) << name_ << ": the map should have changed";
      EXPECT_GE(map_after.known, map_before_.known) << name_;
    } else {
      EXPECT_EQ(map_after, map_before_) << name_ << ": the map should be unchanged";
    }
    std::printf("scenario %-22s %5.2f s:%s; map %s\n", name_.c_str(), seconds, changes.c_str(),
                map_after == map_before_ ? "unchanged" : "changed");
  }

 private:
  std::string name_;
  int index_;
  double t_;
  Counters before_;
  MapDigest map_before_;
};

void pause(double seconds) { ros::WallDuration(seconds).sleep(); }

}  // namespace

// The transform is already in the buffer when the frame comes: fused at once.
TEST(MapperTime, TransformBeforeFrameIsFused) {
  Scenario s("tf_before");
  probe->publishTf(s.frame(), s.t(), s.pose());
  pause(0.2);
  probe->publishFrame(s.frame(), s.t());
  s.finish({{"frames_integrated", 1}}, true);
}

// The frame waits in the queue; its transform comes half a second later,
// well within ~tf_wait, and the frame is fused then, not before.
TEST(MapperTime, TransformAfterFrameWithinTheWaitIsFused) {
  Scenario s("tf_after");
  probe->publishFrame(s.frame(), s.t());
  pause(0.5);
  EXPECT_EQ(s.delta("frames_integrated"), 0u);
  probe->publishTf(s.frame(), s.t(), s.pose());
  s.finish({{"frames_integrated", 1}}, true);
}

// No transform ever: the frame is dropped after ~tf_wait, counted, not fused.
TEST(MapperTime, MissingTransformDropsAfterTheWait) {
  Scenario s("tf_never");
  const ros::WallTime sent = ros::WallTime::now();
  probe->publishFrame(s.frame(), s.t());
  s.finish({{"dropped_no_transform", 1}}, false);
  EXPECT_GE((ros::WallTime::now() - sent).toSec(), kTfWait - 0.1) << "dropped before ~tf_wait";
}

// Only transforms older than the frame: the node must not extrapolate them
// forward (nor take the latest one), so the frame is dropped after the wait.
TEST(MapperTime, StaleTransformIsNotExtrapolated) {
  Scenario s("stale_tf");
  probe->publishTf(s.frame(), s.t() - 0.5, s.pose());
  probe->publishTf(s.frame(), s.t() - 0.4, s.pose());
  pause(0.2);
  probe->publishFrame(s.frame(), s.t());
  s.finish({{"dropped_no_transform", 1}}, false);
}

// A frame older than every transform of its frame (but less than a second
// older than the newest frame, so no time reset) cannot be placed: dropped
// at once as tf_too_old.
TEST(MapperTime, FrameOlderThanItsTransformsIsDroppedAsTooOld) {
  Scenario s("too_old");
  probe->publishTf(s.frame(), s.t(), s.pose());
  probe->publishTf(s.frame(), s.t() + 0.2, s.pose());
  pause(0.2);
  probe->publishFrame(s.frame(), s.t() + 0.1);
  pause(0.3);
  probe->publishFrame(s.frame(), s.t() - 0.5);
  s.finish({{"frames_integrated", 1}, {"dropped_tf_too_old", 1}}, true);
}

// Frames out of stamp order, each inside the transform history: all fused.
TEST(MapperTime, OutOfOrderFramesAreFused) {
  Scenario s("out_of_order");
  for (int k = 0; k <= 4; ++k) probe->publishTf(s.frame(), s.t() + 0.1 * k, s.pose());
  pause(0.2);
  for (double dt : {0.3, 0.1, 0.2}) {
    probe->publishFrame(s.frame(), s.t() + dt);
    pause(0.1);
  }
  s.finish({{"frames_integrated", 3}}, true);
}

// Two frames with the same stamp are two measurements: both fused, none
// dropped, and the map gains weight twice.
TEST(MapperTime, DuplicateStampsAreBothFused) {
  Scenario s("duplicate");
  probe->publishTf(s.frame(), s.t(), s.pose());
  pause(0.2);
  probe->publishFrame(s.frame(), s.t());
  pause(0.1);
  probe->publishFrame(s.frame(), s.t());
  s.finish({{"frames_integrated", 2}}, true);
}

TEST(MapperTime, ZeroStampIsDropped) {
  Scenario s("zero_stamp");
  probe->publishTf(s.frame(), s.t(), s.pose());
  pause(0.2);
  probe->publishFrame(s.frame(), 0.0);
  s.finish({{"dropped_zero_stamp", 1}}, false);
}

TEST(MapperTime, EmptyFrameIdIsDropped) {
  Scenario s("empty_frame_id");
  probe->publishFrame("", s.t());
  s.finish({{"dropped_no_frame_id", 1}}, false);
}

// A NaN translation or a quaternion far from unit length is refused by tf2
// itself (the frame then has no transform); one slightly off (norm 1.003,
// within tf2's tolerance on the squared norm) reaches the node, whose own
// check (norm within 1e-3) refuses it as bad_transform.
TEST(MapperTime, NanAndNonUnitQuaternionTransformsAreRefused) {
  Scenario s("bad_tf");
  geometry_msgs::TransformStamped nan = probe->transform(s.frame("_nan"), s.t(), s.pose());
  nan.transform.translation.y = std::numeric_limits<double>::quiet_NaN();
  geometry_msgs::TransformStamped scaled = probe->transform(s.frame("_scaled"), s.t(), s.pose());
  scaled.transform.rotation.w = 2.0;
  geometry_msgs::TransformStamped slightly = probe->transform(s.frame("_slightly"), s.t(), s.pose());
  slightly.transform.rotation.w = 1.003;
  for (const auto& t : {nan, scaled, slightly}) probe->publishTf(t);
  pause(0.2);
  for (const char* suffix : {"_nan", "_scaled", "_slightly"}) {
    probe->publishFrame(s.frame(suffix), s.t());
    pause(0.05);
  }
  s.finish({{"dropped_no_transform", 2}, {"dropped_bad_transform", 1}}, false);
}

// Transforms that do not place the frame in the world frame: one for another
// child frame, one from a parent that is not connected to the world frame.
TEST(MapperTime, TransformForTheWrongFrameIsNotUsed) {
  Scenario s("wrong_frame");
  probe->publishTf(s.frame("_other"), s.t(), s.pose());
  probe->publishTf(probe->transform(s.frame(), s.t(), s.pose(), "odom"));
  pause(0.2);
  probe->publishFrame(s.frame(), s.t());
  s.finish({{"dropped_no_transform", 1}}, false);
}

// Six frames wait for a transform that never comes with ~max_pending_frames
// = 4: the two oldest are pushed out at once, the other four time out.
TEST(MapperTime, QueueIsBoundedAndCountsWhatItPushesOut) {
  Scenario s("queue_full");
  for (int k = 0; k < 6; ++k) {
    probe->publishFrame(s.frame(), s.t() + 0.01 * k);
    pause(0.06);
  }
  EXPECT_TRUE(MapperProbe::waitUntil([&] { return s.delta("dropped_queue_full") >= 2; }, 10.0));
  EXPECT_EQ(s.delta("dropped_no_transform"), 0u) << "frames timed out before the queue filled";
  s.finish({{"dropped_queue_full", 2}, {"dropped_no_transform", 4}}, false);
}

// The clock and the stamps jump 100 s forward: no reset, frames fused.
TEST(MapperTime, ClockJumpForwardKeepsMapping) {
  Scenario s("jump_forward");
  const double t = s.t() + 100.0;
  probe->setClock(t);
  pause(0.2);
  for (int k = 0; k < 3; ++k) {
    probe->publishTf(s.frame(), t + 0.1 * k, s.pose(k));
    pause(0.05);
    probe->publishFrame(s.frame(), t + 0.1 * k);
    pause(0.1);
  }
  s.finish({{"frames_integrated", 3}}, true);
}

// One pass of a bag over the scenario's stamps t .. t + 4: at each second
// /clock moves there, then the transform comes, then the frame (as rosbag
// plays them). With `frame_first`, the first frame of the pass comes before
// its transform instead, which follows 0.5 s later; `before_transform` runs
// in between.
void playBag(const Scenario& s, bool frame_first = false, const std::function<void()>& before_transform = {}) {
  for (int k = 0; k < 5; ++k) {
    probe->setClock(s.t() + k);
    pause(0.1);
    if (frame_first && k == 0) {
      probe->publishFrame(s.frame(), s.t() + k);
      pause(0.5);
      if (before_transform) before_transform();
      probe->publishTf(s.frame(), s.t() + k, s.pose(k));
      pause(0.2);
      continue;
    }
    probe->publishTf(s.frame(), s.t() + k, s.pose(k));
    pause(0.1);
    probe->publishFrame(s.frame(), s.t() + k);
    pause(0.2);
  }
}

// The first pass of a restart scenario: five frames fused, no reset; returns
// the map after it.
MapDigest firstPass(const Scenario& s) {
  playBag(s);
  EXPECT_TRUE(MapperProbe::waitUntil([&] { return s.delta("frames_integrated") >= 5; }, 10.0));
  EXPECT_EQ(s.delta("frames_integrated"), 5u);
  EXPECT_EQ(s.delta("time_resets"), 0u);
  return probe->digest();
}

// The second pass, after `firstPass`: every frame fused, one reset, nothing
// dropped (the wait lets a late drop show), and the map changed again.
void expectSecondPassFused(Scenario& s, const MapDigest& first_pass) {
  EXPECT_TRUE(MapperProbe::waitUntil([&] { return s.delta("frames_integrated") >= 10; }, 15.0));
  ros::WallDuration(kTfWait + 0.5).sleep();
  EXPECT_EQ(s.delta("frames_integrated"), 10u) << "a frame of the second pass was lost";
  EXPECT_EQ(s.delta("dropped_tf_too_old"), 0u) << "the first replayed frame lost its transform in the reset";
  EXPECT_EQ(s.delta("dropped_no_transform"), 0u);
  EXPECT_EQ(s.delta("time_resets"), 1u);
  EXPECT_EQ(s.delta("dropped_reset"), 0u) << "no frame was waiting when the bag restarted";
  const MapDigest second_pass = probe->digest();
  EXPECT_NE(second_pass, first_pass) << "mapping did not continue after the restart";
  s.finish({{"frames_integrated", 10}, {"time_resets", 1}}, true);
}

// A bag played, then restarted: /clock and the stamps go back 4 s. tf2_ros's
// listener clears the TF buffer when the first transform of the second pass
// comes (the clock went back); the first frame of the second pass then
// resets the queue (time_resets) and must keep that transform, which came
// just before it: all ten frames are fused, none is lost.
TEST(MapperTime, ClockJumpBackResetsAndKeepsTheReplayedTransform) {
  Scenario s("bag_restart");
  const MapDigest first_pass = firstPass(s);
  playBag(s);
  expectSecondPassFused(s, first_pass);
}

// The same restart, but the first replayed frame comes 0.5 s before its
// transform. The buffer still holds the first pass, with a transform at the
// frame's very stamp: the reset must drop it, so the frame is not fused at
// the old pose but waits and is fused when its own transform comes.
TEST(MapperTime, FirstFrameAfterARestartWaitsForItsOwnTransform) {
  Scenario s("restart_frame_first");
  const MapDigest first_pass = firstPass(s);
  uint64_t before_its_transform = 0;
  playBag(s, true, [&] { before_its_transform = s.delta("frames_integrated"); });
  EXPECT_EQ(before_its_transform, 5u) << "fused before its transform came (at a pose of the first pass)";
  expectSecondPassFused(s, first_pass);
}

// After the restart the node maps new frames as before: a frame with its
// transform is fused, one without is dropped after the wait.
TEST(MapperTime, AfterTheRestartFramesAreHandledAsBefore) {
  Scenario s("after_restart");
  probe->publishTf(s.frame(), s.t(), s.pose());
  pause(0.2);
  probe->publishFrame(s.frame(), s.t());
  probe->publishFrame(s.frame("_untracked"), s.t() + 0.1);
  s.finish({{"frames_integrated", 1}, {"dropped_no_transform", 1}}, true);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_mapper_time");
  MapperTestNode node(kDir, "/tsdf_mapper");
  if (!node.ok) return 1;
  probe = &node.probe;
  return RUN_ALL_TESTS();
}
