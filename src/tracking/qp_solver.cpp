#include "surface_nbv/tracking/qp_solver.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace surface_nbv {

Status QpSettings::validate() const {
  if (max_iterations < 1) return Status::Error("max_iterations expected >= 1");
  if (check_every < 1) return Status::Error("check_every expected >= 1");
  if (!std::isfinite(eps_abs) || eps_abs < 0.0) return Status::Error("eps_abs expected >= 0");
  if (!std::isfinite(eps_rel) || eps_rel < 0.0) return Status::Error("eps_rel expected >= 0");
  if (!std::isfinite(rho) || rho <= 0.0) return Status::Error("rho expected > 0");
  if (!std::isfinite(sigma) || sigma <= 0.0) return Status::Error("sigma expected > 0");
  if (!std::isfinite(alpha) || alpha <= 0.0 || alpha >= 2.0) return Status::Error("alpha expected in (0, 2)");
  return Status::Ok();
}

const char* toString(QpStatus status) {
  switch (status) {
    case QpStatus::kSolved: return "solved";
    case QpStatus::kIterationLimit: return "iteration limit";
    case QpStatus::kNotSetUp: return "not set up";
    case QpStatus::kBadInput: return "bad input";
  }
  return "unknown";
}

Status AdmmQpSolver::setup(const Eigen::MatrixXd& P, const Eigen::MatrixXd& A, const QpSettings& settings) {
  ready_ = false;
  if (Status s = settings.validate(); !s) return s;
  const Eigen::Index n = P.rows();
  if (n == 0 || P.cols() != n) return Status::Error("P expected square and non-empty");
  if (A.cols() != n) return Status::Error("A expected to have as many columns as P");
  if (!P.allFinite() || !A.allFinite()) return Status::Error("P and A expected finite");
  if ((P - P.transpose()).cwiseAbs().maxCoeff() > 1e-9 * (1.0 + P.cwiseAbs().maxCoeff())) {
    return Status::Error("P expected symmetric");
  }
  settings_ = settings;
  const double mean_diagonal = P.diagonal().cwiseAbs().mean();
  cost_scale_ = mean_diagonal > 0.0 ? 1.0 / mean_diagonal : 1.0;
  P_ = cost_scale_ * P;
  // Pivoted LDL' of P (plus a rounding allowance): a negative pivot means an indefinite P.
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(P_ + 1e-9 * Eigen::MatrixXd::Identity(n, n));
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return Status::Error("P expected positive semidefinite");
  row_scale_ = A.rowwise().norm().unaryExpr([](double r) { return r > 0.0 ? 1.0 / r : 1.0; });
  A_ = row_scale_.asDiagonal() * A;
  const Eigen::MatrixXd M = P_ + settings_.sigma * Eigen::MatrixXd::Identity(n, n) +
                            settings_.rho * A_.transpose() * A_;
  Eigen::LLT<Eigen::MatrixXd> llt(M);
  if (llt.info() != Eigen::Success) return Status::Error("the ADMM matrix P + sigma I + rho A'A is singular");
  K_ = llt.solve(Eigen::MatrixXd::Identity(n, n));
  KAt_ = K_ * A_.transpose();
  ready_ = true;
  return Status::Ok();
}

QpStatus AdmmQpSolver::solve(const Eigen::MatrixXd& q, const Eigen::MatrixXd& l, const Eigen::MatrixXd& u,
                             QpIterate* it) const {
  if (!ready_) return QpStatus::kNotSetUp;
  const Eigen::Index n = P_.rows(), m = A_.rows(), k = q.cols();
  if (q.rows() != n || l.rows() != m || u.rows() != m || l.cols() != k || u.cols() != k || !q.allFinite() ||
      l.array().isNaN().any() || u.array().isNaN().any() || (l.array() > u.array()).any()) {
    return QpStatus::kBadInput;
  }
  const Eigen::MatrixXd qs = cost_scale_ * q;
  const Eigen::MatrixXd ls = row_scale_.asDiagonal() * l;
  const Eigen::MatrixXd us = row_scale_.asDiagonal() * u;
  Eigen::MatrixXd& x = it->x;
  Eigen::MatrixXd& z = it->z;
  Eigen::MatrixXd& y = it->y;
  if (x.rows() != n || x.cols() != k || !x.allFinite()) x = Eigen::MatrixXd::Zero(n, k);
  if (y.rows() != m || y.cols() != k || !y.allFinite()) y = Eigen::MatrixXd::Zero(m, k);
  z = (A_ * x).cwiseMax(ls).cwiseMin(us);

  const double rho = settings_.rho, sigma = settings_.sigma, alpha = settings_.alpha;
  Eigen::MatrixXd x_tilde(n, k), z_tilde(m, k), z_relaxed(m, k), Px(n, k), Aty(n, k);
  it->iterations = 0;
  for (int i = 1; i <= settings_.max_iterations; ++i) {
    x_tilde.noalias() = K_ * (sigma * x - qs);
    x_tilde.noalias() += KAt_ * (rho * z - y);
    z_tilde.noalias() = A_ * x_tilde;
    x = alpha * x_tilde + (1.0 - alpha) * x;
    z_relaxed = alpha * z_tilde + (1.0 - alpha) * z;
    z = (z_relaxed + y / rho).cwiseMax(ls).cwiseMin(us);
    y += rho * (z_relaxed - z);
    it->iterations = i;
    if (i % settings_.check_every != 0 && i != settings_.max_iterations) continue;
    const Eigen::MatrixXd Ax = A_ * x;
    Px.noalias() = P_ * x;
    Aty.noalias() = A_.transpose() * y;
    it->primal_residual = (Ax - z).cwiseAbs().maxCoeff();
    it->dual_residual = (Px + qs + Aty).cwiseAbs().maxCoeff();
    const double eps_primal =
        settings_.eps_abs + settings_.eps_rel * std::max(Ax.cwiseAbs().maxCoeff(), z.cwiseAbs().maxCoeff());
    const double eps_dual =
        settings_.eps_abs + settings_.eps_rel * std::max({Px.cwiseAbs().maxCoeff(), Aty.cwiseAbs().maxCoeff(),
                                                          qs.cwiseAbs().maxCoeff()});
    if (it->primal_residual <= eps_primal && it->dual_residual <= eps_dual) return QpStatus::kSolved;
  }
  return QpStatus::kIterationLimit;
}

}  // namespace surface_nbv
