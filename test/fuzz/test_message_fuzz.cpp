// Seeded mutation fuzzing of every message the package's nodes take in,
// pushed through the real conversion and validation code: depth images and
// camera infos and clouds (depth_conversions), TSDF updates (fromUpdateMsg,
// then MapMirror::apply), trajectories (fromTrajectoryMsg, then
// TrackerSim::setTrajectory, as mpc_tracker does). Each case starts from a
// valid seed, most are then mutated (fuzz/message_cases.h). Every test checks
// that the accept/refuse decision matches an independent reading of the
// contract where one exists, that accepted outputs are finite and of
// consistent size, and that a refused message leaves the output (or the
// mirror, or the simulated UAV) exactly as it was. Each prints its counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include "contracts.h"
#include "map_digest.h"
#include "message_cases.h"
#include "surface_nbv/map/map_update.h"
#include "surface_nbv/ros/depth_conversions.h"
#include "surface_nbv/ros/map_conversions.h"
#include "surface_nbv/ros/mpc_tracker_server.h"
#include "surface_nbv/tracking/tracker_sim.h"

using namespace surface_nbv;
using namespace surface_nbv::fuzz;

namespace {

constexpr uint32_t kSeed = 20240909;

struct Tally {
  int accepted = 0, rejected = 0, unmutated = 0;

  void print(const char* what) const {
    std::printf("[fuzz] %s: %d cases, %d rejected, %d accepted (%d unmutated seeds)\n", what, accepted + rejected,
                rejected, accepted, unmutated);
    std::fflush(stdout);
  }
  // Both outcomes must be well exercised, or the mutations are off target.
  void expectBothOutcomes(int cases) const {
    EXPECT_EQ(accepted + rejected, cases);
    EXPECT_GE(accepted, cases / 10);
    EXPECT_GE(rejected, cases / 10);
  }
};

}  // namespace

TEST(MessageFuzz, DepthImages) {
  constexpr int kCases = 10000;
  Mutator m(kSeed);
  Tally tally;
  for (int i = 0; i < kCases; ++i) {
    sensor_msgs::Image msg = seedImage(m);
    const bool mutated = m.chance(0.75);
    if (mutated) mutateImage(m, &msg);
    tally.unmutated += mutated ? 0 : 1;
    DepthImage depth;
    depth.resize(3, 2);
    depth.data[0] = 42.0f;  // a sentinel that a refusal must leave alone
    const Status s = fromImageMsg(msg, &depth);
    ASSERT_EQ(s.ok(), imageContractHolds(msg)) << "case " << i << ": " << s.message() << " (encoding '"
                                               << msg.encoding << "', " << msg.width << "x" << msg.height
                                               << ", step " << msg.step << ", " << msg.data.size() << " bytes)";
    if (!s) {
      ++tally.rejected;
      EXPECT_FALSE(s.message().empty());
      ASSERT_EQ(depth.width, 3);
      ASSERT_EQ(depth.height, 2);
      ASSERT_EQ(depth.data.size(), 6u);
      ASSERT_EQ(depth.data[0], 42.0f) << "a refused image changed the output";
      continue;
    }
    ++tally.accepted;
    ASSERT_EQ(depth.width, static_cast<int>(msg.width));
    ASSERT_EQ(depth.height, static_cast<int>(msg.height));
    ASSERT_EQ(depth.data.size(), static_cast<size_t>(msg.width) * msg.height);
    for (uint32_t r = 0; r < msg.height; ++r) {
      for (uint32_t c = 0; c < msg.width; ++c) {
        const float z = depth.at(static_cast<int>(r), static_cast<int>(c));
        ASSERT_TRUE(std::isnan(z) || std::isinf(z) || z > 0.0f) << "depth " << z;
        const float want = referenceDepth(msg, r, c);
        ASSERT_TRUE(sameBits(z, want) || (std::isnan(z) && std::isnan(want))) << z << " vs " << want;
      }
    }
  }
  tally.print("sensor_msgs/Image (depth)");
  tally.expectBothOutcomes(kCases);
}

TEST(MessageFuzz, CameraInfos) {
  constexpr int kCases = 5000;
  Mutator m(kSeed + 1);
  Tally tally;
  CameraConfig base;
  base.min_range = 0.3;
  base.max_range = 9.0;
  for (int i = 0; i < kCases; ++i) {
    sensor_msgs::CameraInfo msg = seedCameraInfo(m);
    const bool mutated = m.chance(0.75);
    if (mutated) mutateCameraInfo(m, &msg);
    tally.unmutated += mutated ? 0 : 1;
    const DepthCamera sentinel(base);
    DepthCamera camera = sentinel;
    const Status s = fromCameraInfoMsg(msg, base, &camera);
    if (!mutated) {
      ASSERT_TRUE(s.ok()) << "a valid camera_info was refused: " << s.message();
    }
    if (!s) {
      ++tally.rejected;
      ASSERT_EQ(camera.fx(), sentinel.fx());
      ASSERT_EQ(camera.cx(), sentinel.cx());
      ASSERT_EQ(camera.width(), sentinel.width()) << "a refused camera_info changed the output";
      continue;
    }
    ++tally.accepted;
    ASSERT_EQ(camera.width(), static_cast<int>(msg.width));
    ASSERT_EQ(camera.height(), static_cast<int>(msg.height));
    ASSERT_EQ(camera.fx(), msg.K[0]);
    ASSERT_EQ(camera.fy(), msg.K[4]);
    ASSERT_TRUE(camera.config().validate().ok()) << camera.config().validate().message();
    ASSERT_EQ(camera.config().min_range, base.min_range);
    ASSERT_TRUE(std::isfinite(camera.cx()) && std::isfinite(camera.cy()));
    // Rays through the corners are finite, and a point on the centre ray
    // projects back onto the centre pixel.
    for (double col : {-0.5, camera.width() - 0.5}) {
      for (double row : {-0.5, camera.height() - 0.5}) {
        ASSERT_TRUE(camera.pixelRay(col, row).allFinite()) << "K = " << msg.K[0] << " " << msg.K[2];
      }
    }
    const double col0 = 0.5 * (camera.width() - 1), row0 = 0.5 * (camera.height() - 1);
    double col = -1.0, row = -1.0;
    ASSERT_TRUE(camera.project(2.0 * camera.pixelRay(col0, row0), &col, &row));
    EXPECT_NEAR(col, col0, 1e-6 * camera.width());
    EXPECT_NEAR(row, row0, 1e-6 * camera.height());
  }
  tally.print("sensor_msgs/CameraInfo");
  tally.expectBothOutcomes(kCases);
}

TEST(MessageFuzz, PointClouds) {
  constexpr int kCases = 10000;
  Mutator m(kSeed + 2);
  Tally tally;
  for (int i = 0; i < kCases; ++i) {
    sensor_msgs::PointCloud2 msg = seedCloud(m);
    const bool mutated = m.chance(0.75);
    if (mutated) mutateCloud(m, &msg);
    tally.unmutated += mutated ? 0 : 1;
    std::vector<Eigen::Vector3f> points(1, Eigen::Vector3f(7, 7, 7));
    const Status s = fromPointCloud2Msg(msg, &points);
    uint64_t offsets[3] = {0, 0, 0};
    const bool valid = cloudContractHolds(msg, offsets);
    ASSERT_EQ(s.ok(), valid) << "case " << i << ": " << s.message() << " (" << msg.fields.size() << " fields, "
                             << msg.width << "x" << msg.height << ", point_step " << msg.point_step
                             << ", row_step " << msg.row_step << ", " << msg.data.size() << " bytes)";
    if (!s) {
      ++tally.rejected;
      ASSERT_EQ(points.size(), 1u);
      ASSERT_EQ(points[0], Eigen::Vector3f(7, 7, 7)) << "a refused cloud changed the output";
      continue;
    }
    ++tally.accepted;
    ASSERT_EQ(points.size(), static_cast<size_t>(msg.width) * msg.height);
    for (uint32_t r = 0; msg.width > 0 && r < msg.height; ++r) {
      for (uint32_t c = 0; c < msg.width; ++c) {
        const size_t base = static_cast<size_t>(r) * msg.row_step + static_cast<size_t>(c) * msg.point_step;
        for (int k = 0; k < 3; ++k) {
          ASSERT_LE(base + offsets[k] + 4, msg.data.size()) << "a point lies beyond the data";
          float want;
          std::memcpy(&want, msg.data.data() + base + offsets[k], 4);
          ASSERT_TRUE(sameBits(points[static_cast<size_t>(r) * msg.width + c][k], want));
        }
      }
    }
  }
  tally.print("sensor_msgs/PointCloud2");
  tally.expectBothOutcomes(kCases);
}

// A publisher map evolves and sends updates (a snapshot first, and whenever
// the mirror asks); most are mutated on the way. Refused updates must leave
// the mirror's digest unchanged; applied ones must be held bit for bit and
// keep the map sound; valid in-order updates must never be refused.
TEST(MessageFuzz, TsdfUpdates) {
  constexpr int kCases = 5000;
  Mutator m(kSeed + 3);
  Tally tally;
  const TsdfConfig config = fuzzMapConfig();
  TsdfMap publisher(config);
  MapMirror mirror(config);
  uint64_t sequence = 0, since = 0;
  bool want_snapshot = true;
  int per_result[5] = {0, 0, 0, 0, 0};
  for (int i = 0; i < kCases; ++i) {
    scribbleMap(&publisher, m.below(3), m);
    const bool snapshot = want_snapshot || m.chance(0.05);
    MapUpdate made;
    ASSERT_TRUE(makeUpdate(publisher, since, ++sequence, snapshot, &made).ok());
    since = publisher.changeCounter();
    surface_nbv::TsdfUpdate msg;
    toUpdateMsg(made, std_msgs::Header(), &msg);
    const bool mutated = m.chance(0.6);
    if (mutated) mutateUpdate(m, &msg);
    tally.unmutated += mutated ? 0 : 1;

    MapUpdate update;
    fromUpdateMsg(msg, &update);
    const bool in_order = mirror.synced() && sequence == mirror.lastSequence() + 1;
    const uint64_t before = mirrorDigest(mirror);
    const ApplyResult result = mirror.apply(update);
    ++per_result[static_cast<int>(result)];
    if (result != ApplyResult::kApplied) {
      ++tally.rejected;
      ASSERT_EQ(mirrorDigest(mirror), before) << "case " << i << ": a " << toString(result)
                                              << " update changed the mirror (" << mirror.lastError() << ")";
      ASSERT_FALSE(mirror.lastError().empty());
      ASSERT_TRUE(mutated || !(snapshot || in_order)) << "a valid update was refused: " << mirror.lastError();
      // A publisher answers a refusal (or a lost update) with a snapshot.
      want_snapshot = true;
      continue;
    }
    ++tally.accepted;
    want_snapshot = false;
    ASSERT_EQ(mapFault(mirror.map()), "") << "case " << i;
    ASSERT_TRUE(mapHoldsUpdate(mirror.map(), update)) << "case " << i << ": the mirror lost part of an update";
    ASSERT_EQ(mirror.lastSequence(), update.sequence);
    if (!mutated && snapshot) {
      // A valid snapshot makes the mirror equal to the publisher.
      ASSERT_EQ(mirror.map().numBlocks(), publisher.numBlocks());
      ASSERT_TRUE(mapHoldsUpdate(mirror.map(), made));
    }
    if (mutated) want_snapshot = true;  // the publisher's map and the mirror's may now differ
  }
  tally.print("surface_nbv/TsdfUpdate");
  std::printf("[fuzz] TsdfUpdate results: %d applied, %d ignored, %d need_snapshot, %d incompatible, %d malformed\n",
              per_result[0], per_result[1], per_result[2], per_result[3], per_result[4]);
  tally.expectBothOutcomes(kCases);
  EXPECT_GT(per_result[static_cast<int>(ApplyResult::kMalformed)], kCases / 20);
  EXPECT_GT(per_result[static_cast<int>(ApplyResult::kIncompatible)], kCases / 20);
}

TEST(MessageFuzz, Trajectories) {
  constexpr int kCases = 3000;
  Mutator m(kSeed + 4);
  Tally tally;
  TrackerSimConfig config;
  UavState initial;
  initial.p_W = Eigen::Vector3d(1.0, -2.0, 1.5);
  for (int i = 0; i < kCases; ++i) {
    TrackerSim sim(config, initial);
    sim.runUntil(m.uniform(0.0, 0.3));
    const UavState state = sim.state();
    trajectory_msgs::MultiDOFJointTrajectory msg = seedTrajectory(m, state.p_W);
    const bool mutated = m.chance(0.75);
    if (mutated) mutateTrajectory(m, &msg);
    tally.unmutated += mutated ? 0 : 1;

    Trajectory trajectory;
    Status s = fromTrajectoryMsg(msg, sim.time(), &trajectory);
    if (s) s = sim.setTrajectory(trajectory);
    if (!mutated) {
      ASSERT_TRUE(s.ok()) << "a valid trajectory was refused: " << s.message();
    }
    if (!s) {
      ++tally.rejected;
      ASSERT_EQ(sim.mode(), TrackerMode::kHolding);
      ASSERT_EQ(sim.state().p_W, state.p_W) << "a refused trajectory moved the UAV";
      ASSERT_EQ(sim.reference().p_W, state.p_W);
      continue;
    }
    ++tally.accepted;
    ASSERT_EQ(sim.mode(), TrackerMode::kTracking);
    ASSERT_EQ(trajectory.size(), msg.points.size());
    for (size_t k = 0; k < trajectory.size(); ++k) {
      const TrajectoryPoint& p = trajectory.points()[k];
      ASSERT_TRUE(std::isfinite(p.t) && p.p_W.allFinite() && std::isfinite(p.yaw) && p.v_W.allFinite());
      if (k > 0) {
        ASSERT_GT(p.t, trajectory.points()[k - 1].t);
      }
      // The yaw is that of the rotation the message means (its quaternion normalised).
      const geometry_msgs::Quaternion& q = msg.points[k].transforms.at(0).rotation;
      const Eigen::Quaterniond rotation = Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized();
      const Eigen::Vector3d heading = rotation * Eigen::Vector3d::UnitX();
      ASSERT_NEAR(std::remainder(p.yaw - std::atan2(heading.y(), heading.x()), 2.0 * M_PI), 0.0, 5e-3)
          << "point " << k << " of case " << i;
    }
    for (int k = 0; k < 5; ++k) {
      const TrajectorySample sample = trajectory.sample(m.uniform(trajectory.startTime() - 1, trajectory.endTime() + 1));
      ASSERT_TRUE(sample.p_W.allFinite() && sample.v_W.allFinite() && std::isfinite(sample.yaw));
    }
    sim.runUntil(sim.time() + 0.2);
    ASSERT_TRUE(sim.state().p_W.allFinite() && sim.state().v_W.allFinite() && std::isfinite(sim.state().yaw));
  }
  tally.print("trajectory_msgs/MultiDOFJointTrajectory");
  tally.expectBothOutcomes(kCases);
}
