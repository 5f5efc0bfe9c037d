#include "conform/registration/degeneracy.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "plane_matrix.h"

namespace conform {

namespace {

// A degenerate motion whose rotation part (in the scaled coordinates, of a unit vector) is below this is a pure
// translation; above, a rotation. Exact subspaces give 0 or O(1); noise leaves ~1e-3.
constexpr double kPureTranslation = 0.1;

// Eigenvalues at least this fraction of the largest (std within 10 times the best-fixed direction's) are measured.
constexpr double kMeasuredRelative = 1e-2;

// v or -v, whichever has its largest component positive, so that a report does not flip with rounding.
Eigen::Vector3d canonical(const Eigen::Vector3d& v) {
  Eigen::Index i = 0;
  v.cwiseAbs().maxCoeff(&i);
  return v(i) < 0.0 ? Eigen::Vector3d(-v) : v;
}

// The columns of the identity for the free degrees of freedom (rx ry rz tx ty tz).
Eigen::MatrixXd free_basis(const FreeDof& free_dof) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(6, free_dof.count());
  for (int i = 0, c = 0; i < 6; ++i) {
    if (free_dof.free(i)) P(i, c++) = 1.0;
  }
  return P;
}

// Splits the degenerate subspace D (orthonormal columns) into pure translations and rotations: the right singular
// vectors of D's rotation rows with (near) zero singular value combine to translations, the others to rotations,
// whose axis point is c + w x v / |w|^2 once the degenerate translations are taken out of v.
// `scaled_covariance` (of the scaled twist) gives each motion its predicted standard deviation; zero: none.
void split_motions(const Eigen::MatrixXd& D, const Matrix6d& H, double largest, const Matrix6d& scaled_covariance,
                   DegeneracyReport& report) {
  const Eigen::MatrixXd W = D.topRows(3);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(W, Eigen::ComputeFullV);
  const Eigen::MatrixXd V = svd.matrixV();
  const Eigen::VectorXd sigma = svd.singularValues();
  struct Twist {
    Vector6d x;  // scaled: (w L, v)
    double relative_eigenvalue;
  };
  std::vector<Twist> rotations;
  std::vector<Eigen::Vector3d> translations;
  for (Eigen::Index j = 0; j < V.cols(); ++j) {
    const Vector6d x = D * V.col(j);
    const double relative = largest > 0.0 ? x.dot(H * x) / largest : 0.0;
    if ((j < sigma.size() ? sigma(j) : 0.0) >= kPureTranslation) {
      rotations.push_back({x, relative});
      continue;
    }
    DegenerateDirection d;
    d.kind = MotionKind::kTranslation;
    d.direction = canonical(x.tail<3>().normalized());
    d.point = report.centre;
    d.relative_eigenvalue = relative;
    d.std_mm = std::sqrt(std::max(0.0, x.dot(scaled_covariance * x)));
    translations.push_back(d.direction);
    report.directions.push_back(d);
  }
  for (const Twist& t : rotations) {
    // The twist moves p by w x (p - c) + v; its axis passes through c + w x v / |w|^2 with pitch w . v / |w|^2.
    const Eigen::Vector3d w = canonical(t.x.head<3>()) / report.length_scale_mm;
    const double sign = t.x.head<3>().dot(w) < 0.0 ? -1.0 : 1.0;
    Eigen::Vector3d v = sign * t.x.tail<3>();
    for (const Eigen::Vector3d& u : translations) v -= v.dot(u) * u;
    DegenerateDirection d;
    d.kind = MotionKind::kRotation;
    d.direction = w.normalized();
    d.point = report.centre + w.cross(v) / w.squaredNorm();
    d.pitch_mm_per_rad = w.dot(v) / w.squaredNorm();
    d.relative_eigenvalue = t.relative_eigenvalue;
    d.std_rad =
        std::sqrt(std::max(0.0, t.x.dot(scaled_covariance * t.x))) * t.x.head<3>().norm() / report.length_scale_mm;
    report.directions.push_back(d);
  }
}

// Records the degenerate eigen-directions (indices into the solver's) and splits them into motions.
void record_degenerate(const Eigen::MatrixXd& P, const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& solver,
                       const std::vector<Eigen::Index>& degenerate, const PlaneNormalMatrix& matrix, double largest,
                       const Matrix6d& scaled_covariance, DegeneracyReport& report) {
  if (degenerate.empty()) return;
  Eigen::MatrixXd D(6, static_cast<Eigen::Index>(degenerate.size()));
  for (std::size_t k = 0; k < degenerate.size(); ++k) {
    D.col(static_cast<Eigen::Index>(k)) = P * solver.eigenvectors().col(degenerate[k]);
    report.degenerate_basis.push_back(D.col(static_cast<Eigen::Index>(k)));
  }
  if (report.length_scale_mm > 0.0) split_motions(D, matrix.H, largest, scaled_covariance, report);
}

// A + (S - A)_+ for A = U diag(a) U^T (U: the free eigenvectors, orthonormal columns; a > 0) and
// S = U diag(1/lambda) U^T C U diag(1/lambda) U^T / N, the cluster-robust sandwich: in A's whitened coordinates
// (y = diag(a)^-1/2 U^T x) A is the identity and the positive part is that of X - I, X = diag(a)^-1/2 U^T S U
// diag(a)^-1/2, which keeps a tube axis' huge variance from swamping the millimetre ones in rounding.
Matrix6d bound_by_cluster_sandwich(const Eigen::MatrixXd& U, const Eigen::VectorXd& a, const Eigen::VectorXd& lambda,
                                   const Matrix6d& C, double count) {
  const Eigen::Index k = U.cols();
  const Eigen::VectorXd root = a.cwiseSqrt();
  Eigen::MatrixXd X = U.transpose() * C * U / count;  // the middle, in the eigenbasis
  for (Eigen::Index i = 0; i < k; ++i) {
    for (Eigen::Index j = 0; j < k; ++j) X(i, j) /= lambda(i) * lambda(j) * root(i) * root(j);
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> excess(X - Eigen::MatrixXd::Identity(k, k));
  Eigen::MatrixXd Y = Eigen::MatrixXd::Identity(k, k);
  for (Eigen::Index i = 0; i < k; ++i) {
    const double e = excess.eigenvalues()(i);
    if (e > 0.0) Y.noalias() += e * excess.eigenvectors().col(i) * excess.eigenvectors().col(i).transpose();
  }
  const Eigen::MatrixXd B = U * root.asDiagonal();
  return B * Y * B.transpose();
}

DegeneracyReport start_report(const PlaneNormalMatrix& matrix) {
  DegeneracyReport report;
  report.centre = matrix.centre;
  report.length_scale_mm = matrix.length_scale_mm;
  return report;
}

}  // namespace

std::vector<DegenerateDirection> motions_of(const std::vector<Vector6d>& basis, const DegeneracyReport& report,
                                            const Matrix6d& H) {
  DegeneracyReport out = start_report(PlaneNormalMatrix{});
  out.centre = report.centre;
  out.length_scale_mm = report.length_scale_mm;
  if (basis.empty() || !(report.length_scale_mm > 0.0)) return {};
  Eigen::MatrixXd D(6, static_cast<Eigen::Index>(basis.size()));
  for (std::size_t k = 0; k < basis.size(); ++k) D.col(static_cast<Eigen::Index>(k)) = basis[k].normalized();
  // Orthonormal columns spanning the same subspace, as split_motions expects.
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(D);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(6, D.cols());
  Vector6d scale;
  const double L = report.length_scale_mm;
  scale << L, L, L, 1.0, 1.0, 1.0;
  const Matrix6d scaled_covariance = scale.asDiagonal() * report.covariance * scale.asDiagonal();
  const double largest = report.eigenvalues.size() > 0 ? report.eigenvalues(report.eigenvalues.size() - 1) : 0.0;
  split_motions(Q, H, largest, scaled_covariance, out);
  return out.directions;
}

double DegeneracyReport::relative_smallest() const {
  if (eigenvalues.size() == 0 || !(eigenvalues(eigenvalues.size() - 1) > 0.0)) return 0.0;
  return eigenvalues(0) / eigenvalues(eigenvalues.size() - 1);
}

PlaneNormalMatrix plane_normal_matrix(const std::vector<Eigen::Vector3d>& q, const std::vector<Eigen::Vector3d>& n) {
  return detail::plane_normal_matrix_of(
      q.size() < n.size() ? q.size() : n.size(), [&](std::size_t i) -> const Eigen::Vector3d& { return q[i]; },
      [&](std::size_t i) -> const Eigen::Vector3d& { return n[i]; });
}

void add_cluster_moment(const std::vector<Eigen::Vector3d>& q, const std::vector<Eigen::Vector3d>& n,
                        const std::vector<double>& psi, std::size_t clusters, PlaneNormalMatrix& matrix) {
  detail::add_cluster_moment(
      std::min({q.size(), n.size(), psi.size()}), [&](std::size_t i) -> const Eigen::Vector3d& { return q[i]; },
      [&](std::size_t i) -> const Eigen::Vector3d& { return n[i]; }, [&](std::size_t i) { return psi[i]; }, clusters,
      matrix);
}

DegeneracyReport analyze_degeneracy(const PlaneNormalMatrix& matrix, double threshold, const FreeDof& free_dof) {
  DegeneracyReport report = start_report(matrix);
  report.threshold = threshold;
  const Eigen::MatrixXd P = free_basis(free_dof);
  if (P.cols() == 0) return report;
  const Eigen::MatrixXd Hf = P.transpose() * matrix.H * P;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(Hf);
  report.eigenvalues = solver.eigenvalues().cwiseMax(0.0);
  const double largest = report.eigenvalues(report.eigenvalues.size() - 1);
  std::vector<Eigen::Index> degenerate;
  for (Eigen::Index i = 0; i < report.eigenvalues.size(); ++i) {
    if (!(report.eigenvalues(i) >= threshold * largest) || !(largest > 0.0)) degenerate.push_back(i);
  }
  record_degenerate(P, solver, degenerate, matrix, largest, Matrix6d::Zero(), report);
  return report;
}

DegeneracyReport analyze_constraint(const PlaneNormalMatrix& matrix, double noise_mm, double tolerance_mm,
                                    double tolerance_rad, const FreeDof& free_dof, double min_relative,
                                    double start_std_mm, double start_std_rad) {
  DegeneracyReport report = start_report(matrix);
  report.noise_mm = noise_mm;
  report.tolerance_mm = tolerance_mm;
  report.tolerance_rad = tolerance_rad;
  const Eigen::MatrixXd P = free_basis(free_dof);
  const double L = matrix.length_scale_mm;
  if (P.cols() == 0 || !(L > 0.0)) return report;
  const Eigen::MatrixXd Hf = P.transpose() * matrix.H * P;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(Hf);
  report.eigenvalues = solver.eigenvalues().cwiseMax(0.0);
  const double largest = report.eigenvalues(report.eigenvalues.size() - 1);
  const double count = static_cast<double>(matrix.count);
  // An exactly unconstrained direction gets the variance of an eigenvalue 1e-15 of the largest: huge, finite.
  const double floor = std::max(largest * 1e-15, 1e-300);
  const Eigen::Index k = report.eigenvalues.size();
  const Eigen::MatrixXd U = P * solver.eigenvectors();
  // The covariance from the robust fit's own bread (PlaneNormalMatrix::bread), H when it is not known.
  Eigen::MatrixXd Ub = U;
  Eigen::VectorXd lambdas = report.eigenvalues;
  if (!matrix.bread.isZero(0.0)) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> bread(P.transpose() * matrix.bread * P);
    Ub = P * bread.eigenvectors();
    lambdas = bread.eigenvalues().cwiseMax(0.0);
  }
  Eigen::VectorXd variances(k);
  Matrix6d scaled_covariance = Matrix6d::Zero();
  for (Eigen::Index i = 0; i < k; ++i) {
    const Vector6d u = Ub.col(i);
    // sigma^2 (N A)^-1 along the eigenvector: the Gauss-Newton covariance of the scaled twist.
    lambdas(i) = std::max(lambdas(i), floor);
    // The sandwich sees the residuals where this direction is measured; away from the optimum they are the pose's
    // error, not noise, so only the robust noise decides what is held (else a wrong start would hold itself).
    variances(i) = std::max(noise_mm * noise_mm / (count * lambdas(i)),
                            u.dot(matrix.residual_moment * u) / (count * lambdas(i) * lambdas(i)));
    scaled_covariance.noalias() += variances(i) * u * u.transpose();
  }
  if (matrix.clusters > 1 && variances.minCoeff() > 0.0) {
    scaled_covariance = bound_by_cluster_sandwich(Ub, variances, lambdas, matrix.cluster_moment, count);
  }
  std::vector<Eigen::Index> degenerate;
  for (Eigen::Index i = 0; i < k; ++i) {
    const Vector6d u = U.col(i);
    const double variance = std::max(0.0, u.dot(scaled_covariance * u));
    ConstraintDirection d;
    d.rotation = u.head<3>() / L;
    d.translation = u.tail<3>();
    d.relative_eigenvalue = largest > 0.0 ? report.eigenvalues(i) / largest : 0.0;
    d.std_rad = std::sqrt(variance) * d.rotation.norm();
    d.std_mm = std::sqrt(variance) * d.translation.norm();
    // sigma / sqrt(N lambda) along H's eigenvector: what decides the hold, whatever the kernel discounts.
    const double gaussian_std = noise_mm / std::sqrt(count * std::max(report.eigenvalues(i), floor));
    // A direction measured within a factor of ten of the best (in std) is never held: holding it cannot beat the
    // data, however noisy (a LiDAR scene's residuals are centimetres).
    // Held only where the data cannot do better than the start: loose beyond the tolerance and the start's std.
    const bool loose = gaussian_std * d.rotation.norm() > std::max(tolerance_rad, start_std_rad) ||
                       gaussian_std * d.translation.norm() > std::max(tolerance_mm, start_std_mm);
    d.held = !(largest > 0.0) || d.relative_eigenvalue < min_relative ||
             (loose && d.relative_eigenvalue < kMeasuredRelative);
    if (d.held) degenerate.push_back(i);
    report.eigen_directions.push_back(d);
  }
  Vector6d scale;
  scale << 1.0 / L, 1.0 / L, 1.0 / L, 1.0, 1.0, 1.0;
  report.covariance = scale.asDiagonal() * scaled_covariance * scale.asDiagonal();
  report.std = report.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  record_degenerate(P, solver, degenerate, matrix, largest, scaled_covariance, report);
  return report;
}

double largest_displacement_std_mm(const DegeneracyReport& report, const std::vector<Eigen::Vector3d>& points) {
  const double L = report.length_scale_mm;
  double worst = 0.0;
  for (const Eigen::Vector3d& p : points) {
    double variance = 0.0;
    for (const ConstraintDirection& d : report.eigen_directions) {
      if (d.held) continue;
      // The direction is a unit 6-vector in (rotation x L, translation): its coefficient's std from the two parts.
      const double coefficient_variance = std::pow(d.std_rad * L, 2) + std::pow(d.std_mm, 2);
      variance += coefficient_variance * (d.rotation.cross(p - report.centre) + d.translation).squaredNorm();
    }
    worst = std::max(worst, variance);
  }
  return std::sqrt(worst);
}

}  // namespace conform
