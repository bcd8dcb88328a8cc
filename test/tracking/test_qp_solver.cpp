#include "surface_nbv/tracking/qp_solver.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

using namespace surface_nbv;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

QpSettings tight() {
  QpSettings s;
  s.max_iterations = 5000;
  s.eps_abs = 1e-9;
  s.eps_rel = 1e-9;
  return s;
}

}  // namespace

// min 1/2 |x - (3, -1)|^2 s.t. 0 <= x <= 1: the optimum is the projection (1, 0).
TEST(AdmmQpSolver, BoxProjectionOptimum) {
  AdmmQpSolver solver;
  ASSERT_TRUE(solver.setup(Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Identity(), tight()));
  QpIterate it;
  EXPECT_EQ(solver.solve(Eigen::Vector2d(-3, 1), Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), &it),
            QpStatus::kSolved);
  EXPECT_NEAR(it.x(0), 1.0, 1e-6);
  EXPECT_NEAR(it.x(1), 0.0, 1e-6);
}

// min 1/2 |x|^2 - 2 x1 - 2 x2 s.t. x1 + x2 <= 1 (a general row): KKT gives (0.5, 0.5)
// with multiplier 1.5; and x1 - x2 in [-inf, inf] does nothing.
TEST(AdmmQpSolver, GeneralRowKnownOptimum) {
  Eigen::Matrix2d A;
  A << 1, 1, 1, -1;
  AdmmQpSolver solver;
  ASSERT_TRUE(solver.setup(Eigen::Matrix2d::Identity(), A, tight()));
  QpIterate it;
  EXPECT_EQ(solver.solve(Eigen::Vector2d(-2, -2), Eigen::Vector2d(-kInf, -kInf), Eigen::Vector2d(1, kInf), &it),
            QpStatus::kSolved);
  EXPECT_NEAR(it.x(0), 0.5, 1e-6);
  EXPECT_NEAR(it.x(1), 0.5, 1e-6);
}

// Several right-hand sides at once give the same answers as one at a time,
// and an inactive constraint set gives the closed form -P^-1 q.
TEST(AdmmQpSolver, ColumnsAreIndependentAndMatchClosedForm) {
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  const int n = 8;
  Eigen::MatrixXd B = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return g(rng); });
  const Eigen::MatrixXd P = B * B.transpose() + Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd q = Eigen::MatrixXd::NullaryExpr(n, 3, [&] { return g(rng); });
  AdmmQpSolver solver;
  ASSERT_TRUE(solver.setup(P, Eigen::MatrixXd::Identity(n, n), tight()));
  const Eigen::MatrixXd lo = Eigen::MatrixXd::Constant(n, 3, -1e3), hi = Eigen::MatrixXd::Constant(n, 3, 1e3);
  QpIterate all;
  ASSERT_EQ(solver.solve(q, lo, hi, &all), QpStatus::kSolved);
  const Eigen::MatrixXd closed = -P.ldlt().solve(q);
  EXPECT_LT((all.x - closed).cwiseAbs().maxCoeff(), 1e-6);
  for (int c = 0; c < 3; ++c) {
    QpIterate one;
    ASSERT_EQ(solver.solve(q.col(c), lo.col(c), hi.col(c), &one), QpStatus::kSolved);
    EXPECT_LT((one.x - all.x.col(c)).cwiseAbs().maxCoeff(), 1e-6);
  }
}

// The iteration cap holds, and a warm start from the optimum converges at once.
TEST(AdmmQpSolver, IterationCapAndWarmStart) {
  QpSettings s;
  s.max_iterations = 3;
  AdmmQpSolver solver;
  ASSERT_TRUE(solver.setup(Eigen::Matrix2d::Identity() * 1e3, Eigen::Matrix2d::Identity(), s));
  QpIterate it;
  EXPECT_EQ(solver.solve(Eigen::Vector2d(-5e3, 1e3), Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), &it),
            QpStatus::kIterationLimit);
  EXPECT_EQ(it.iterations, 3);

  AdmmQpSolver precise;
  ASSERT_TRUE(precise.setup(Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Identity(), tight()));
  QpIterate cold;
  ASSERT_EQ(precise.solve(Eigen::Vector2d(-3, 1), Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), &cold),
            QpStatus::kSolved);
  QpIterate warm = cold;
  ASSERT_EQ(precise.solve(Eigen::Vector2d(-3, 1), Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), &warm),
            QpStatus::kSolved);
  EXPECT_LT(warm.iterations, cold.iterations);
}

TEST(AdmmQpSolver, RefusesBadProblems) {
  AdmmQpSolver solver;
  QpIterate it;
  EXPECT_EQ(solver.solve(Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), &it),
            QpStatus::kNotSetUp);
  Eigen::Matrix2d asymmetric;
  asymmetric << 1, 1, 0, 1;
  EXPECT_FALSE(solver.setup(asymmetric, Eigen::Matrix2d::Identity()));
  EXPECT_FALSE(solver.setup(-Eigen::Matrix2d::Identity() * 10, Eigen::Matrix2d::Identity()));
  QpSettings bad;
  bad.alpha = 2.0;
  EXPECT_NE(bad.validate().message().find("alpha"), std::string::npos);
  ASSERT_TRUE(solver.setup(Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Identity()));
  EXPECT_EQ(solver.solve(Eigen::Vector2d(NAN, 0), Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), &it),
            QpStatus::kBadInput);
  EXPECT_EQ(solver.solve(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), Eigen::Vector2d::Zero(), &it),
            QpStatus::kBadInput);
}
