#include "surface_nbv/tracking/mpc_tracker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

using namespace surface_nbv;

namespace {

// The documented MPC cost of an input sequence (one position axis), evaluated
// by simulating the exact discretization: no matrix of MpcTracker is reused.
double axisCost(const MpcConfig& c, double drag, double p0, double v0, double a_prev, const Eigen::VectorXd& p_ref,
                const Eigen::VectorXd& v_ref, const Eigen::VectorXd& a) {
  const AxisDiscretization d = discretizeAxis(drag, c.dt);
  double p = p0, v = v0, cost = 0.0, previous = a_prev;
  for (int k = 0; k < c.horizon; ++k) {
    p += d.beta * v + d.gamma * a[k];
    v = d.alpha * v + d.beta * a[k];
    const double w = k + 1 == c.horizon ? c.q_terminal : 1.0;
    cost += w * (c.q_position * std::pow(p - p_ref[k], 2) + c.q_velocity * std::pow(v - v_ref[k], 2));
    cost += c.r_acceleration * std::pow(a[k] - drag * v_ref[k], 2);
    cost += c.r_acceleration_change * std::pow(a[k] - previous, 2);
    previous = a[k];
  }
  return cost;
}

// Minimiser of a quadratic given as a function, from its Hessian and gradient
// at zero, both found by evaluating it at unit vectors.
Eigen::VectorXd quadraticMinimiser(int n, const std::function<double(const Eigen::VectorXd&)>& f) {
  const double f0 = f(Eigen::VectorXd::Zero(n));
  Eigen::VectorXd fi(n);
  for (int i = 0; i < n; ++i) fi[i] = f(Eigen::VectorXd::Unit(n, i));
  Eigen::MatrixXd H(n, n);
  Eigen::VectorXd g(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      H(i, j) = f(Eigen::VectorXd::Unit(n, i) + Eigen::VectorXd::Unit(n, j)) - fi[i] - fi[j] + f0;
    }
    g[i] = fi[i] - f0 - 0.5 * H(i, i);
  }
  return -H.ldlt().solve(g);
}

}  // namespace

TEST(MpcTracker, ConfigNamesBadKey) {
  EXPECT_TRUE(MpcConfig().validate());
  MpcConfig c;
  c.horizon = 0;
  EXPECT_NE(c.validate().message().find("horizon"), std::string::npos);
  c = MpcConfig();
  c.q_position = -1;
  EXPECT_NE(c.validate().message().find("q_position"), std::string::npos);
  c = MpcConfig();
  c.qp.max_iterations = 0;
  EXPECT_NE(c.validate().message().find("qp: max_iterations"), std::string::npos);
}

// Small offsets keep every limit inactive: the first input equals the
// unconstrained closed-form optimum of the documented cost, per axis and for yaw.
TEST(MpcTracker, MatchesUnconstrainedClosedForm) {
  for (bool tight : {false, true}) {
    MpcConfig c;
    if (tight) {
      c.qp.max_iterations = 20000;
      c.qp.eps_abs = c.qp.eps_rel = 1e-10;
    }
    UavModelConfig model;
    MpcTracker mpc(c, model);
    UavState state;
    state.p_W = Eigen::Vector3d(0.05, -0.1, 1.0);
    state.v_W = Eigen::Vector3d(0.1, 0.0, -0.05);
    state.yaw = 0.3;
    UavCommand previous;
    previous.a_W = Eigen::Vector3d(0.05, -0.02, 0.0);
    previous.yaw_rate = 0.05;
    MpcReference ref = MpcReference::hold(Eigen::Vector3d(0.1, 0.0, 1.02), 0.4, c.horizon);
    for (int k = 0; k < c.horizon; ++k) ref.v_W.col(k) = Eigen::Vector3d(0.05, 0.02 * k / c.horizon, 0.0);
    const MpcResult result = mpc.solve(state, ref, previous);
    ASSERT_NE(result.status, MpcStatus::kInvalidInput);
    const double tolerance = tight ? 1e-6 : 2e-3;
    for (int i = 0; i < 3; ++i) {
      const Eigen::VectorXd p_ref = ref.p_W.row(i).transpose(), v_ref = ref.v_W.row(i).transpose();
      const Eigen::VectorXd best = quadraticMinimiser(c.horizon, [&](const Eigen::VectorXd& a) {
        return axisCost(c, model.drag, state.p_W[i], state.v_W[i], previous.a_W[i], p_ref, v_ref, a);
      });
      ASSERT_LT(best.cwiseAbs().maxCoeff(), 0.5 * model.a_max) << "the limits must stay inactive";
      EXPECT_NEAR(result.command.a_W[i], best[0], tolerance) << "axis " << i << (tight ? " tight" : " default");
    }
    // Yaw: a single integrator with a constant reference (rate reference 0).
    const Eigen::VectorXd best_rate = quadraticMinimiser(c.horizon, [&](const Eigen::VectorXd& r) {
      double yaw = state.yaw, cost = 0.0, last = previous.yaw_rate;
      for (int k = 0; k < c.horizon; ++k) {
        yaw += c.dt * r[k];
        const double w = k + 1 == c.horizon ? c.q_terminal : 1.0;
        cost += w * c.q_yaw * std::pow(yaw - 0.4, 2) + c.r_yaw_rate * r[k] * r[k] +
                c.r_yaw_rate_change * std::pow(r[k] - last, 2);
        last = r[k];
      }
      return cost;
    });
    EXPECT_NEAR(result.command.yaw_rate, best_rate[0], tolerance);
  }
}

// Random states (some beyond the velocity box) and references (some 100 m
// away, some non-finite): every command is finite, inside the acceleration and
// yaw-rate boxes, and keeps the next velocity inside the box when it can. The
// boxes are the model's (the MPC has none of its own): the default UAV's and a
// slower one's.
TEST(MpcTracker, CommandsAlwaysInsideLimits) {
  UavModelConfig slow;
  slow.v_max = 0.6;
  slow.a_max = 0.8;
  slow.yaw_rate_max = 0.4;
  for (const UavModelConfig& model : {UavModelConfig(), slow}) {
    MpcConfig c;
    MpcTracker mpc(c, model);
    EXPECT_DOUBLE_EQ(mpc.model().v_max, model.v_max);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const AxisDiscretization d = discretizeAxis(model.drag, c.dt);
    UavCommand previous;
    for (int trial = 0; trial < 500; ++trial) {
      UavState state;
      state.p_W = 10 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      state.v_W = (trial % 7 == 0 ? 3.0 : 1.0) * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      state.yaw = M_PI * unit(rng);
      const double reach = trial % 3 == 0 ? 100.0 : 2.0;
      MpcReference ref = MpcReference::hold(state.p_W + reach * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)),
                                            1e4 * unit(rng), c.horizon);
      ref.v_W.setConstant(5.0 * unit(rng));
      if (trial % 11 == 0) ref.p_W(1, 4) = NAN;
      const MpcResult r = mpc.solve(state, ref, previous);
      ASSERT_TRUE(r.command.a_W.allFinite() && std::isfinite(r.command.yaw_rate));
      ASSERT_LE(r.command.a_W.cwiseAbs().maxCoeff(), model.a_max);
      ASSERT_LE(std::abs(r.command.yaw_rate), model.yaw_rate_max);
      for (int i = 0; i < 3; ++i) {
        const double v_next = d.alpha * state.v_W[i] + d.beta * r.command.a_W[i];
        if (std::abs(state.v_W[i]) <= model.v_max) {
          ASSERT_LE(std::abs(v_next), model.v_max + 1e-12);
        } else {
          ASSERT_LT(std::abs(v_next), std::abs(state.v_W[i]));  // braking towards the box
        }
      }
      if (trial % 11 == 0) {
        EXPECT_EQ(r.status, MpcStatus::kInvalidInput);
      }
      previous = r.command;
    }
    UavState broken;
    broken.v_W.x() = NAN;
    const MpcResult r = mpc.solve(broken, MpcReference::hold(Eigen::Vector3d::Zero(), 0, c.horizon), previous);
    EXPECT_EQ(r.status, MpcStatus::kInvalidInput);
    EXPECT_TRUE(r.command.a_W.allFinite());
  }
}

// The QP's predicted velocities honour the box (the constraint is in the
// solver, not only in the final projection): a far target saturates them.
TEST(MpcTracker, PredictionRespectsVelocityBox) {
  MpcConfig c;
  c.qp.max_iterations = 2000;
  UavModelConfig model;
  MpcTracker mpc(c, model);
  UavState state;
  const MpcResult r = mpc.solve(state, MpcReference::hold(Eigen::Vector3d(50, -50, 0), 0, c.horizon), UavCommand());
  ASSERT_EQ(r.status, MpcStatus::kSolved) << r.iterations;
  const Eigen::Matrix3Xd& p = r.predicted_p_W;
  double max_speed = 0.0;
  for (int k = 1; k < c.horizon; ++k) {
    max_speed = std::max(max_speed, ((p.col(k) - p.col(k - 1)) / c.dt).cwiseAbs().maxCoeff());
  }
  EXPECT_LE(max_speed, model.v_max * 1.01);
  EXPECT_GT(max_speed, model.v_max * 0.9);
}
