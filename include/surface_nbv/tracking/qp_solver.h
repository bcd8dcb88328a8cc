// A dense QP solver with a bounded run time for the MPC:
//   min 1/2 x'Px + q'x   s.t.   l <= Ax <= u,
// solved for k right-hand sides at once (columns of q, l, u) sharing P and A,
// e.g. the three position axes of the MPC.
//
// Method: ADMM as in OSQP (Stellato et al. 2020): x-update with the matrix
// (P + sigma I + rho A'A), z-update by projection onto [l, u], dual ascent,
// over-relaxation alpha. Why this one: in the condensed MPC, P and A depend
// only on the configuration, so setup() inverts the KKT matrix once and each
// iteration is a few dense products (no factorisation per step, no active-set
// changes whose count is hard to bound); velocity limits are general rows
// (A = prediction matrix) and acceleration limits are identity rows, both
// handled alike; the iteration count is capped so the time per solve is
// bounded, and the previous solution warm-starts the next. Its weakness,
// modest accuracy, is harmless for control; callers that need exact limits
// project the applied input (see clampAcceleration). Rows of A are scaled to
// unit norm and P to unit mean diagonal internally. Not thread-safe per object.
#pragma once

#include "surface_nbv/common.h"
#include "surface_nbv/util/status.h"

namespace surface_nbv {

struct QpSettings {
  int max_iterations = 300;  // the time bound
  int check_every = 5;       // residuals are computed every this many iterations
  double eps_abs = 1e-4;     // on the scaled problem
  double eps_rel = 1e-4;
  double rho = 1.0;          // ADMM penalty (scaled problem)
  double sigma = 1e-6;       // proximal term, keeps the x-update well posed for P = 0
  double alpha = 1.6;        // over-relaxation in (0, 2)

  Status validate() const;
};

enum class QpStatus { kSolved, kIterationLimit, kNotSetUp, kBadInput };
const char* toString(QpStatus status);

// Iterates of the scaled problem: pass the same object again to warm-start.
struct QpIterate {
  Eigen::MatrixXd x;  // n x k, the solution (unscaled)
  Eigen::MatrixXd z;  // m x k, A x projected onto the bounds (scaled rows)
  Eigen::MatrixXd y;  // m x k, duals (scaled rows and cost)
  int iterations = 0;
  double primal_residual = 0.0, dual_residual = 0.0;
};

class AdmmQpSolver {
 public:
  // P: n x n symmetric positive semidefinite; A: m x n. Precomputes the inverse.
  Status setup(const Eigen::MatrixXd& P, const Eigen::MatrixXd& A, const QpSettings& settings = QpSettings());

  // q: n x k, l and u: m x k with l <= u (+-infinity allowed). Warm-starts from
  // *iterate when its x (and y) have the right sizes, else starts at zero.
  QpStatus solve(const Eigen::MatrixXd& q, const Eigen::MatrixXd& l, const Eigen::MatrixXd& u,
                 QpIterate* iterate) const;

  int variables() const { return static_cast<int>(P_.rows()); }
  int constraints() const { return static_cast<int>(A_.rows()); }

 private:
  QpSettings settings_;
  Eigen::MatrixXd P_;         // scaled by cost_scale_
  Eigen::MatrixXd A_;         // rows scaled by row_scale_
  Eigen::VectorXd row_scale_;
  double cost_scale_ = 1.0;
  Eigen::MatrixXd K_;         // (P + sigma I + rho A'A)^-1
  Eigen::MatrixXd KAt_;       // K A'
  bool ready_ = false;
};

}  // namespace surface_nbv
