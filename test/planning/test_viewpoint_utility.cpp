// The one viewpoint / cluster utility (surface/viewpoint_utility.h, eq. 3 and
// eq. 5 of docs/method.md) and the tour-head reranking built on it
// (planning/tour_head.h).
#include "surface_nbv/surface/viewpoint_utility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "surface_nbv/planning/tour_head.h"

using namespace surface_nbv;

namespace {

using Gain = std::function<double(const Eigen::Vector4d&)>;

Eigen::Vector4d at(double x, double y, double z) { return Eigen::Vector4d(x, y, z, 0.0); }

// The gain of each viewpoint is its yaw component, so a tour carries its gains.
Eigen::Vector4d at(double x, double y, double z, double gain) { return Eigen::Vector4d(x, y, z, gain); }
const Gain kYawGain = [](const Eigen::Vector4d& q) { return q.w(); };

}  // namespace

TEST(ViewpointUtility, ClusterGainIsTheShareOfIsesSeen) {
  EXPECT_DOUBLE_EQ(clusterGain(3, 4), 0.75);
  EXPECT_DOUBLE_EQ(clusterGain(0, 4), 0.0);
  EXPECT_DOUBLE_EQ(clusterGain(7, 7), 1.0);
  EXPECT_EQ(clusterGain(0, 0), 0.0);
  EXPECT_EQ(clusterGain(5, 0), 0.0);
}

TEST(ViewpointUtility, EdgeUtilityIsEq5) {
  // 0.5 exp(-0.1 * 2 - 0.2 * 3) = 0.5 exp(-0.8)
  EXPECT_NEAR(edgeUtility(0.5, 2.0, 3.0, 0.1, 0.2), 0.22466448205861078, 1e-15);
  // 0.8 exp(-0.3 * 4 - 0.03 * 10) = 0.8 exp(-1.5), the default lambdas
  EXPECT_NEAR(edgeUtility(0.8, 4.0, 10.0, 0.3, 0.03), 0.17850412811874386, 1e-15);
  EXPECT_DOUBLE_EQ(edgeUtility(0.8, 0.0, 0.0, 0.3, 0.03), 0.8);   // no travel: the gain
  EXPECT_DOUBLE_EQ(edgeUtility(0.8, 50.0, 9.0, 0.0, 0.0), 0.8);   // no decay: the gain
  EXPECT_DOUBLE_EQ(edgeUtility(0.0, 1.0, 1.0, 0.3, 0.03), 0.0);
  // The two travels are weighted separately: 1 m between clusters costs what
  // 10 m inside one does at lambda_tc = 10 lambda_ic.
  EXPECT_NEAR(edgeUtility(1.0, 1.0, 0.0, 0.3, 0.03), edgeUtility(1.0, 0.0, 10.0, 0.3, 0.03), 1e-15);
  EXPECT_LT(edgeUtility(1.0, 2.0, 0.0, 0.3, 0.03), edgeUtility(1.0, 0.0, 2.0, 0.3, 0.03));
  // The long distances of a big scene underflow to 0, never below.
  EXPECT_EQ(edgeUtility(1.0, 1e4, 0.0, 0.3, 0.03), 0.0);
}

TEST(ViewpointUtility, LogCostIsMinusLogOfTheUtilityOverGMax) {
  EXPECT_NEAR(utilityLogCost(0.8, 4.0, 10.0, 0.3, 0.03, 1.0), 1.7231435513142097, 1e-14);
  EXPECT_NEAR(utilityLogCost(0.5, 2.0, 3.0, 0.1, 0.2, 2.0), 0.1 * 2 + 0.2 * 3 + std::log(4.0), 1e-12);
  const double g_max = 0.9;
  for (double gain : {0.01, 0.2, 0.5, 0.9}) {
    for (double d_kl : {0.0, 1.5, 12.0}) {
      for (double d_lm : {0.0, 0.7, 30.0}) {
        const double f = edgeUtility(gain, d_kl, d_lm, 0.3, 0.03);
        const double cost = utilityLogCost(gain, d_kl, d_lm, 0.3, 0.03, g_max);
        EXPECT_NEAR(cost, -std::log(f / g_max), 1e-12) << gain << " " << d_kl << " " << d_lm;
        EXPECT_GE(cost, 0.0);
      }
    }
  }
  // 0 exactly for the best possible arc: gain g_max, no travel.
  EXPECT_DOUBLE_EQ(utilityLogCost(0.9, 0.0, 0.0, 0.3, 0.03, 0.9), 0.0);
  // Finite where f_uv underflows (the terms, not -log 0).
  EXPECT_EQ(edgeUtility(0.5, 1e4, 0.0, 0.3, 0.03), 0.0);
  const double far = utilityLogCost(0.5, 1e4, 0.0, 0.3, 0.03, 1.0);
  EXPECT_TRUE(std::isfinite(far));
  EXPECT_NEAR(far, 3000.0 + std::log(2.0), 1e-9);
}

TEST(ViewpointUtility, SumCostRangeAndOrder) {
  EXPECT_DOUBLE_EQ(kSumCostScale, 10.0);
  EXPECT_DOUBLE_EQ(utilitySumCost(0.0, 0.5), kSumCostScale);
  EXPECT_DOUBLE_EQ(utilitySumCost(0.5, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(utilitySumCost(0.25, 0.5), 0.5 * kSumCostScale);  // linear in f_uv
  EXPECT_DOUBLE_EQ(utilitySumCost(0.1, 0.4), 0.75 * kSumCostScale);
  // Clamped to [0, kSumCostScale] outside 0 <= f_uv <= g_max.
  EXPECT_DOUBLE_EQ(utilitySumCost(0.6, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(utilitySumCost(-0.1, 0.5), kSumCostScale);
  // Both costs order single arcs alike: decreasing in f_uv.
  double last_log = -1.0, last_sum = -1.0;
  for (double d : {0.0, 1.0, 2.0, 5.0, 20.0}) {
    const double f = edgeUtility(0.7, d, 1.0, 0.3, 0.03);
    const double log_cost = utilityLogCost(0.7, d, 1.0, 0.3, 0.03, 1.0), sum_cost = utilitySumCost(f, 1.0);
    EXPECT_GT(log_cost, last_log);
    EXPECT_GT(sum_cost, last_sum);
    EXPECT_GE(sum_cost, 0.0);
    EXPECT_LE(sum_cost, kSumCostScale);
    last_log = log_cost, last_sum = sum_cost;
  }
}

TEST(ViewpointUtility, HeadUtilityIsEq5ForOneViewpoint) {
  EXPECT_NEAR(headUtility(2.0, 5.0, 0.1), 1.2130613194252668, 1e-15);
  EXPECT_DOUBLE_EQ(headUtility(2.0, 0.0, 0.3), 2.0);
  EXPECT_DOUBLE_EQ(headUtility(2.0, 100.0, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(headUtility(0.0, 1.0, 0.3), 0.0);
  // Eq. 5 with only the inter-cluster travel.
  EXPECT_DOUBLE_EQ(headUtility(0.6, 3.5, 0.3), edgeUtility(0.6, 3.5, 0.0, 0.3, 0.0));
}

TEST(TourHead, NearerViewpointBeatsASlightlyBetterFarOne) {
  const Eigen::Vector4d uav = at(0, 0, 2);
  // 1.0 e^(-0.3 * 2) = 0.55 against 1.1 e^(-0.3 * 10) = 0.055.
  const std::vector<Eigen::Vector4d> far_first = {at(10, 0, 2, 1.1), at(0, 2, 2, 1.0)};
  const std::vector<Eigen::Vector4d> near_first = {at(0, 2, 2, 1.0), at(10, 0, 2, 1.1)};
  EXPECT_EQ(bestTourHead(far_first, uav, 2, 0.3, 1.0, kYawGain), 1u);
  EXPECT_EQ(bestTourHead(near_first, uav, 2, 0.3, 1.0, kYawGain), 0u);
  // lambda = 0: distance does not count, the higher gain wins wherever it is.
  EXPECT_EQ(bestTourHead(far_first, uav, 2, 0.0, 1.0, kYawGain), 0u);
  EXPECT_EQ(bestTourHead(near_first, uav, 2, 0.0, 1.0, kYawGain), 1u);
  // A gain far enough ahead pays for the distance: 10 e^(-3) = 0.5 < 0.55 < 20 e^(-3) = 1.0.
  EXPECT_EQ(bestTourHead({at(0, 2, 2, 1.0), at(10, 0, 2, 10.0)}, uav, 2, 0.3, 1.0, kYawGain), 0u);
  EXPECT_EQ(bestTourHead({at(0, 2, 2, 1.0), at(10, 0, 2, 20.0)}, uav, 2, 0.3, 1.0, kYawGain), 1u);
}

TEST(TourHead, VerticalScaleMakesAClimbCostMore) {
  const Eigen::Vector4d uav = at(0, 0, 2);
  // 3 m above the UAV, 4 m beside it at its height, the same gain.
  const std::vector<Eigen::Vector4d> tour = {at(0, 0, 5, 1.0), at(4, 0, 2, 1.0)};
  EXPECT_EQ(bestTourHead(tour, uav, 2, 0.3, 1.0, kYawGain), 0u);  // 3 m against 4 m
  EXPECT_EQ(bestTourHead(tour, uav, 2, 0.3, 1.2, kYawGain), 0u);  // 3.6 m against 4 m
  EXPECT_EQ(bestTourHead(tour, uav, 2, 0.3, 1.5, kYawGain), 1u);  // 4.5 m against 4 m
  EXPECT_EQ(bestTourHead(tour, uav, 2, 0.3, 0.0, kYawGain), 0u);  // a climb is free
  // A move across does not feel the scale.
  const std::vector<Eigen::Vector4d> level = {at(5, 0, 2, 1.0), at(0, 4, 2, 1.0)};
  EXPECT_EQ(bestTourHead(level, uav, 2, 0.3, 3.0, kYawGain), 1u);
}

TEST(TourHead, LookaheadBoundsAndTies) {
  const Eigen::Vector4d uav = at(0, 0, 2);
  int calls = 0;
  const Gain counting = [&calls](const Eigen::Vector4d& q) { return ++calls, q.w(); };
  EXPECT_EQ(bestTourHead({}, uav, 5, 0.3, 1.0, counting), 0u);
  const std::vector<Eigen::Vector4d> tour = {at(8, 0, 2, 1.0), at(6, 0, 2, 1.0), at(1, 0, 2, 1.0)};
  EXPECT_EQ(bestTourHead(tour, uav, 0, 0.3, 1.0, counting), 0u);
  EXPECT_EQ(calls, 0) << "lookahead 0 and an empty tour rank nothing";
  EXPECT_EQ(bestTourHead(tour, uav, 1, 0.3, 1.0, counting), 0u);
  EXPECT_EQ(bestTourHead(tour, uav, 2, 0.3, 1.0, counting), 1u);   // the nearest is beyond the lookahead
  EXPECT_EQ(bestTourHead(tour, uav, 3, 0.3, 1.0, counting), 2u);
  EXPECT_EQ(bestTourHead(tour, uav, 100, 0.3, 1.0, counting), 2u);  // clamped to the tour
  EXPECT_EQ(calls, 1 + 2 + 3 + 3);
  // Ties go to the earliest; gains of 0 everywhere keep the tour's order.
  EXPECT_EQ(bestTourHead({at(0, 3, 2, 1.0), at(3, 0, 2, 1.0)}, uav, 2, 0.3, 1.0, kYawGain), 0u);
  EXPECT_EQ(bestTourHead({at(5, 0, 2, 0.0), at(1, 0, 2, 0.0)}, uav, 2, 0.3, 1.0, kYawGain), 0u);
  // A NaN gain never wins.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(bestTourHead({at(5, 0, 2, 0.1), at(1, 0, 2, nan)}, uav, 2, 0.3, 1.0, kYawGain), 0u);
  EXPECT_EQ(bestTourHead({at(1, 0, 2, nan), at(5, 0, 2, 0.1)}, uav, 2, 0.3, 1.0, kYawGain), 1u);
}
