// Contact normal by logistic regression (Nairn, Hammerquist & Smith 2020, ref. [6] of Nairn 2026;
// algorithm as summarised in the extraction nairn-2026-fmpm.md §2.5). The particles of field a
// (label -1) and field b (label +1) that see a contact node are separated by the surface
//   f(x) = 2 / (1 + exp(-(beta . x + beta_0))) - 1 = tanh((beta . x + beta_0) / 2),
// fitted by damped Gauss-Newton least squares on sum_p (y_p - f(x_p))^2 + lambda |beta|^2.
// The normal from a to b is beta / |beta|. Coordinates are relative to the node and in cell units,
// so the penalties are the extraction's 1e-7 dx^2 on beta and 0.1 on beta_0 in the linear start.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <span>

#include "matpoint/core/types.hpp"

namespace matpoint {

template <int D>
struct LabelledPoint {
  Vec<D> x;      // position relative to the node, in cell sizes
  double label;  // -1 (field a) or +1 (field b)
};

template <int D>
struct LogisticNormal {
  Vec<D> normal = Vec<D>::Zero();  // unit, from the -1 points to the +1 points
  bool found = false;              // false: degenerate points (use another normal)
  int iterations = 0;              // Gauss-Newton iterations taken
};

namespace logistic_detail {

constexpr double kNormalPenalty = 1e-7;   // on |beta|^2 (extraction §2.5: 1e-7 dx^2)
constexpr double kOffsetPenalty = 0.1;    // on beta_0^2 in the linear start
constexpr double kAngleTolerance = 1e-5;  // stop when 1 - cos(change of the normal) is below
constexpr int kMaxIterations = 15;
constexpr int kMaxHalvings = 10;

template <int D>
using Params = Eigen::Matrix<double, D + 1, 1>;

template <int D>
Params<D> augmented(const Vec<D>& x) {
  Params<D> a;
  a.template head<D>() = x;
  a[D] = 1.0;
  return a;
}

template <int D>
double objective(std::span<const LabelledPoint<D>> points, const Params<D>& beta) {
  double sum = kNormalPenalty * beta.template head<D>().squaredNorm();
  for (const auto& p : points) {
    const double r = p.label - std::tanh(0.5 * beta.dot(augmented<D>(p.x)));
    sum += r * r;
  }
  return sum;
}

/// 1 - cos of the angle between the normal parts of two parameter vectors.
template <int D>
double angle_change(const Params<D>& a, const Params<D>& b) {
  const double na = a.template head<D>().norm(), nb = b.template head<D>().norm();
  return 1.0 - a.template head<D>().dot(b.template head<D>()) / (na * nb);
}

}  // namespace logistic_detail

/// The logistic-regression normal of `points`; needs at least one point of each label.
template <int D>
LogisticNormal<D> logistic_normal(std::span<const LabelledPoint<D>> points) {
  using namespace logistic_detail;
  using Matrix = Eigen::Matrix<double, D + 1, D + 1>;
  LogisticNormal<D> result;
  // Linear start: least squares y ~ beta . x + beta_0, coefficients times 2 (f ~ z / 2 near 0).
  Matrix A = Matrix::Zero();
  Params<D> rhs = Params<D>::Zero();
  int negative = 0, positive = 0;
  for (const auto& p : points) {
    const Params<D> a = augmented<D>(p.x);
    A += a * a.transpose();
    rhs += p.label * a;
    (p.label < 0 ? negative : positive) += 1;
  }
  if (negative == 0 || positive == 0) return result;  // nothing to separate
  A.diagonal().template head<D>().array() += kNormalPenalty;
  A(D, D) += kOffsetPenalty;
  Params<D> beta = 2.0 * A.ldlt().solve(rhs);
  if (!beta.allFinite() || !(beta.template head<D>().norm() > 0.0)) return result;

  double current = objective<D>(points, beta);
  for (int it = 0; it < kMaxIterations; ++it) {
    // Gauss-Newton on the residuals r_p = y_p - f_p, df/dz = (1 - f^2) / 2.
    Matrix H = Matrix::Zero();
    Params<D> g = Params<D>::Zero();
    for (const auto& p : points) {
      const Params<D> a = augmented<D>(p.x);
      const double f = std::tanh(0.5 * beta.dot(a));
      const double slope = 0.5 * (1.0 - f * f);
      H += (slope * slope) * (a * a.transpose());
      g += (slope * (p.label - f)) * a;
    }
    H.diagonal().template head<D>().array() += kNormalPenalty;
    g.template head<D>() -= kNormalPenalty * beta.template head<D>();
    const Params<D> step = H.ldlt().solve(g);
    if (!step.allFinite()) break;
    // Damping: halve the step until the objective does not grow.
    double factor = 1.0;
    Params<D> trial = beta + step;
    double value = objective<D>(points, trial);
    for (int h = 0; h < kMaxHalvings && !(value <= current); ++h) {
      factor *= 0.5;
      trial = beta + factor * step;
      value = objective<D>(points, trial);
    }
    if (!(value <= current) || !(trial.template head<D>().norm() > 0.0)) break;
    const double change = angle_change<D>(beta, trial);
    beta = trial;
    current = value;
    result.iterations = it + 1;
    if (change < kAngleTolerance) break;
  }
  result.normal = beta.template head<D>().normalized();
  result.found = result.normal.allFinite();
  return result;
}

}  // namespace matpoint
