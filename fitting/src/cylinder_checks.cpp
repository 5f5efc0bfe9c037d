#include "cylinder_checks.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "conform/core/constants.h"
#include "conform/core/nearest_neighbors.h"

namespace conform::detail {
namespace {

constexpr double kMadToSigma = 1.482602218505602;  // 1 / Phi^-1(3/4)

double median_in_place(std::vector<double>& values) {
  if (values.empty()) return 0.0;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

// Radial unit direction of p about the model's axis and its height along it.
void radial(const Cylinder& model, const Eigen::Vector3d& p, Eigen::Vector3d* n, double* z) {
  const Eigen::Vector3d q = p - model.axis_point;
  *z = q.dot(model.axis_direction);
  const Eigen::Vector3d r = q - *z * model.axis_direction;
  const double rho = r.norm();
  *n = rho > 0.0 ? Eigen::Vector3d(r / rho) : Eigen::Vector3d::Zero();
}

}  // namespace

double median_abs(std::vector<double> values) {
  for (double& v : values) v = std::abs(v);
  return median_in_place(values);
}

double robust_sigma(std::vector<double> values) { return kMadToSigma * median_abs(std::move(values)); }

double local_noise_sigma(const std::vector<Eigen::Vector3d>& points, int k) {
  const int neighbours = std::min<int>(std::max(k, 4), static_cast<int>(points.size()));
  if (neighbours < 4) return 0.0;
  const KdTree tree(points);
  const std::size_t stride = std::max<std::size_t>(1, points.size() / 512);
  std::vector<double> sigmas;
  std::vector<int> idx;
  std::vector<float> d2;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    tree.knn(points[i].cast<float>(), neighbours, idx, d2);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int j : idx) mean += points[static_cast<std::size_t>(j)];
    mean /= static_cast<double>(idx.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (int j : idx) {
      const Eigen::Vector3d d = points[static_cast<std::size_t>(j)] - mean;
      scatter.noalias() += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter, Eigen::EigenvaluesOnly);
    // The plane through k points takes 3 degrees of freedom: E[smallest eigenvalue] = (k - 3) sigma^2.
    sigmas.push_back(std::sqrt(std::max(0.0, solver.eigenvalues()(0)) / static_cast<double>(idx.size() - 3)));
  }
  return median_in_place(sigmas);
}

double arc_span(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& indices, const Cylinder& model) {
  constexpr int kBins = 720;
  if (indices.empty()) return 0.0;
  const Eigen::Vector3d e1 = model.axis_direction.unitOrthogonal();
  const Eigen::Vector3d e2 = model.axis_direction.cross(e1);
  const auto azimuth = [&](int i, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    const Eigen::Vector3d q = points[static_cast<std::size_t>(i)] - model.axis_point;
    return std::atan2(q.dot(v), q.dot(u));
  };
  std::vector<bool> filled(kBins, false);
  for (int i : indices) {
    const double phi = azimuth(i, e1, e2) + kTwoPi / 2.0;  // [0, 2 pi]
    filled[static_cast<std::size_t>(std::min(kBins - 1, static_cast<int>(phi / kTwoPi * kBins)))] = true;
  }
  // Widest run of empty bins, going round the circle (twice, to catch a run across bin 0).
  int widest = 0, widest_end = 0, run = 0;
  for (int b = 0; b < 2 * kBins; ++b) {
    run = filled[static_cast<std::size_t>(b % kBins)] ? 0 : run + 1;
    if (std::min(run, kBins) > widest) {
      widest = std::min(run, kBins);
      widest_end = b;
    }
  }
  const double binned = kTwoPi * static_cast<double>(kBins - widest) / kBins;
  if (binned > kTwoPi / 2.0) return binned;
  // Up to half a turn the bins are too coarse (a plane seen as a huge cylinder fills one bin): measure the azimuths
  // from the middle of the filled range, where none of them wraps.
  const double middle =
      (static_cast<double>(widest_end) + 1.0 + 0.5 * static_cast<double>(kBins - widest)) / kBins * kTwoPi -
      kTwoPi / 2.0;
  const Eigen::Vector3d u = std::cos(middle) * e1 + std::sin(middle) * e2;
  const Eigen::Vector3d v = model.axis_direction.cross(u);
  double lo = kTwoPi, hi = -kTwoPi;
  for (int i : indices) {
    const double phi = azimuth(i, u, v);
    lo = std::min(lo, phi);
    hi = std::max(hi, phi);
  }
  return hi - lo;
}

CylinderSide wall_side(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                       const std::vector<int>& indices, const Cylinder& model) {
  std::size_t outward = 0;
  std::size_t inward = 0;
  for (int i : indices) {
    Eigen::Vector3d n;
    double z = 0.0;
    radial(model, points[static_cast<std::size_t>(i)], &n, &z);
    const double c = n.dot(normals[static_cast<std::size_t>(i)]);
    outward += c > 0.0 ? 1 : 0;
    inward += c < 0.0 ? 1 : 0;
  }
  const double total = static_cast<double>(indices.size());
  if (total > 0.0 && static_cast<double>(outward) >= 0.9 * total) return CylinderSide::kOuter;
  if (total > 0.0 && static_cast<double>(inward) >= 0.9 * total) return CylinderSide::kInner;
  return CylinderSide::kUnknown;
}

double plane_rms(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& indices) {
  if (indices.size() < 3) return 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i : indices) mean += points[static_cast<std::size_t>(i)];
  mean /= static_cast<double>(indices.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (int i : indices) {
    const Eigen::Vector3d d = points[static_cast<std::size_t>(i)] - mean;
    scatter.noalias() += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, solver.eigenvalues()(0)) / static_cast<double>(indices.size()));
}

double sphere_median(const std::vector<Eigen::Vector3d>& points) {
  // Centred (the points already are) and scaled to unit size, the 4 x 4 normal equations of this linear fit are well
  // conditioned; it only has to tell a sphere from a cylinder, not measure one.
  double scale = 0.0;
  for (const auto& p : points) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  if (!(scale > 0.0)) return std::numeric_limits<double>::infinity();
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  for (const auto& point : points) {
    const Eigen::Vector3d p = point / scale;
    const Eigen::Vector4d row(2.0 * p.x(), 2.0 * p.y(), 2.0 * p.z(), 1.0);
    normal.noalias() += row * row.transpose();
    rhs += p.squaredNorm() * row;
  }
  const Eigen::LDLT<Eigen::Matrix4d> ldlt(normal);
  if (ldlt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const Eigen::Vector4d x = ldlt.solve(rhs);
  const Eigen::Vector3d c = x.head<3>();
  const double r2 = x(3) + c.squaredNorm();
  if (!(r2 > 0.0) || !std::isfinite(r2)) return std::numeric_limits<double>::infinity();
  const double r = std::sqrt(r2);
  std::vector<double> residuals(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) residuals[i] = scale * ((points[i] / scale - c).norm() - r);
  return median_abs(std::move(residuals));
}

CylinderCovariance cylinder_covariance(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& inliers,
                                       const Cylinder& model) {
  CylinderCovariance out;
  const Eigen::Vector3d& a = model.axis_direction;
  const Eigen::Vector3d e1 = a.unitOrthogonal();
  const Eigen::Vector3d e2 = a.cross(e1);
  out.frame << e1, e2, a;
  if (inliers.size() <= 5) return out;
  Eigen::Matrix<double, 5, 5> normal = Eigen::Matrix<double, 5, 5>::Zero();
  double sum_squares = 0.0;
  for (int i : inliers) {
    Eigen::Vector3d n;
    double z = 0.0;
    radial(model, points[static_cast<std::size_t>(i)], &n, &z);
    Eigen::Matrix<double, 5, 1> row;
    row << -z * n.dot(e1), -z * n.dot(e2), -n.dot(e1), -n.dot(e2), -1.0;
    normal.noalias() += row * row.transpose();
    const double d = signed_distance(model, points[static_cast<std::size_t>(i)]);
    sum_squares += d * d;
  }
  const double variance = sum_squares / static_cast<double>(inliers.size() - 5);
  const Eigen::LDLT<Eigen::Matrix<double, 5, 5>> ldlt(normal);
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0.0)) {
    out.covariance.setConstant(std::numeric_limits<double>::infinity());
    out.radius_std_mm = out.axis_angle_std_rad = out.axis_point_std_mm = std::numeric_limits<double>::infinity();
    return out;
  }
  out.covariance = variance * ldlt.solve(Eigen::Matrix<double, 5, 5>::Identity());
  out.radius_std_mm = std::sqrt(std::max(0.0, out.covariance(4, 4)));
  const Eigen::Matrix2d tilt = out.covariance.block<2, 2>(0, 0);
  const Eigen::Matrix2d shift = out.covariance.block<2, 2>(2, 2);
  out.axis_angle_std_rad =
      std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(tilt).eigenvalues()(1)));
  out.axis_point_std_mm =
      std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(shift).eigenvalues()(1)));
  return out;
}

}  // namespace conform::detail
