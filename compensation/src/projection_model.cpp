#include "conform/compensation/projection_model.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/registration/sicp_pairs.h"

namespace conform {
namespace {

// Spline distances in units of 100 mm keep r^2 log r of a metre-sized part near 1.
constexpr double kScale = 0.01;
constexpr std::size_t kMaxSamples = 20000;

double tps(double r) { return r > 0.0 ? r * r * std::log(r) : 0.0; }

struct Sample {
  Eigen::Vector2d uv;
  double height;
};

// The least-squares plane of the contour in the scan frame, principal direction first.
void fit_plane(const Polyline& contour, ProjectionModel& m) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& c : contour.points) mean += m.T_scan_nominal * c;
  mean /= static_cast<double>(contour.points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& c : contour.points) {
    const Eigen::Vector3d d = m.T_scan_nominal * c - mean;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  m.origin = mean;
  m.normal = eigen.eigenvectors().col(0);
  m.u_axis = eigen.eigenvectors().col(2);
  m.v_axis = m.normal.cross(m.u_axis);
}

// Deviations of the scan from the rigidly placed nominal surface along the plane's normal, at nominal positions.
std::vector<Sample> deviations(const Polyline& contour, const IcpReference& nominal,
                               const std::vector<Eigen::Vector3d>& scan, const ProjectionOptions& o,
                               const ProjectionModel& m) {
  const KdTree contour_tree(contour.points);
  const Eigen::Isometry3d T_nominal_scan = m.T_scan_nominal.inverse();
  const Eigen::Vector3d N_nominal = T_nominal_scan.linear() * m.normal;
  const std::size_t stride = std::max<std::size_t>(1, scan.size() / kMaxSamples);
  std::vector<Sample> samples;
  for (std::size_t i = 0; i < scan.size(); i += stride) {
    const Eigen::Vector3d x = T_nominal_scan * scan[i];
    float sq = 0.0f;
    contour_tree.nearest(x.cast<float>(), &sq);
    if (static_cast<double>(sq) > o.neighbourhood_mm * o.neighbourhood_mm) continue;
    const ReferencePoint r = closest_on_reference(nominal, x, o.max_distance_mm);
    if (!r.found) continue;
    const double along = r.normal.dot(N_nominal);
    if (std::abs(along) < 0.5) continue;  // the edge's flank: it says nothing about the height
    const Eigen::Vector3d y = m.T_scan_nominal * r.point - m.origin;
    samples.push_back({{y.dot(m.u_axis), y.dot(m.v_axis)}, r.normal.dot(x - r.point) / along});
  }
  return samples;
}

Eigen::VectorXd basis(const ProjectionModel& m, const Eigen::Vector2d& uv) {
  if (m.fit == ProjectionFit::kParabola) {
    const double u = kScale * uv.x(), v = kScale * uv.y();
    return Eigen::Vector4d(1.0, u, v, u * u);
  }
  Eigen::VectorXd b(3 + static_cast<Eigen::Index>(m.centres.size()));
  b(0) = 1.0;
  b(1) = kScale * uv.x();
  b(2) = kScale * uv.y();
  for (std::size_t j = 0; j < m.centres.size(); ++j)
    b(3 + static_cast<Eigen::Index>(j)) = tps(kScale * (uv - m.centres[j]).norm());
  return b;
}

}  // namespace

const char* to_string(ProjectionFit fit) { return fit == ProjectionFit::kParabola ? "parabola" : "spline"; }

bool ProjectionOptions::IsValid(std::string* error) const {
  const char* why = nullptr;
  if (!std::isfinite(neighbourhood_mm) || neighbourhood_mm <= 0.0)
    why = "projection neighbourhood must be > 0 mm";
  else if (!std::isfinite(max_distance_mm) || max_distance_mm <= 0.0)
    why = "projection distance must be > 0 mm";
  else if (spline_centres < 3)
    why = "spline centres must be >= 3";
  else if (!std::isfinite(spline_smoothing) || spline_smoothing < 0.0)
    why = "spline smoothing must be >= 0";
  if (why == nullptr) return true;
  if (error != nullptr) *error = why;
  return false;
}

double ProjectionModel::height(const Eigen::Vector2d& uv) const { return basis(*this, uv).dot(coefficients); }

Eigen::Vector2d ProjectionModel::gradient(const Eigen::Vector2d& uv) const {
  const Eigen::VectorXd& c = coefficients;
  Eigen::Vector2d g(kScale * c(1), kScale * c(2));
  if (fit == ProjectionFit::kParabola) {
    g.x() += 2.0 * kScale * kScale * uv.x() * c(3);
    return g;
  }
  for (std::size_t j = 0; j < centres.size(); ++j) {
    const Eigen::Vector2d d = kScale * (uv - centres[j]);
    const double r = d.norm();
    if (r > 0.0) g += c(3 + static_cast<Eigen::Index>(j)) * kScale * d * (2.0 * std::log(r) + 1.0);
  }
  return g;
}

Eigen::Vector3d ProjectionModel::map_point(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d y = T_scan_nominal * p;
  const Eigen::Vector3d d = y - origin;
  return y + height({d.dot(u_axis), d.dot(v_axis)}) * normal;
}

Eigen::Vector3d ProjectionModel::map_normal(const Eigen::Vector3d& p, const Eigen::Vector3d& n) const {
  const Eigen::Vector3d d = T_scan_nominal * p - origin;
  const Eigen::Vector3d rotated = T_scan_nominal.linear() * n;
  const double along = rotated.dot(normal);
  if (std::abs(along) < 0.5) return rotated;  // a normal across the plane: the height field does not tilt it
  const Eigen::Vector2d g = gradient({d.dot(u_axis), d.dot(v_axis)});
  return (rotated - (along > 0.0 ? 1.0 : -1.0) * (g.x() * u_axis + g.y() * v_axis)).normalized();
}

ProjectionModel fit_projection_model(const Polyline& contour, const IcpReference& nominal,
                                     const std::vector<Eigen::Vector3d>& scan, const Eigen::Isometry3d& T,
                                     const ProjectionOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("projection model: " + why);
  if (contour.points.size() < 3) throw Error("projection model: the contour has fewer than 3 points");
  ProjectionModel m;
  m.T_scan_nominal = T;
  m.fit = options.fit;
  fit_plane(contour, m);
  if (m.fit == ProjectionFit::kThinPlateSpline) {
    const auto count = static_cast<std::size_t>(options.spline_centres);
    for (std::size_t j = 0; j < count; ++j) {
      const Eigen::Vector3d y = T * contour.points[j * contour.points.size() / count] - m.origin;
      m.centres.emplace_back(y.dot(m.u_axis), y.dot(m.v_axis));
    }
  }
  const std::vector<Sample> samples = deviations(contour, nominal, scan, options, m);
  const Eigen::Index unknowns = m.fit == ProjectionFit::kParabola ? 4 : 3 + options.spline_centres;
  if (static_cast<Eigen::Index>(samples.size()) < 3 * unknowns) {
    throw Error("projection model: only " + std::to_string(samples.size()) +
                " scan points lie on the contour's neighbourhood; the fit needs " + std::to_string(3 * unknowns));
  }
  const auto rows = static_cast<Eigen::Index>(samples.size());
  const Eigen::Index ridge = m.fit == ProjectionFit::kParabola ? 0 : unknowns - 3;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows + ridge, unknowns);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(rows + ridge);
  for (Eigen::Index i = 0; i < rows; ++i) {
    A.row(i) = basis(m, samples[static_cast<std::size_t>(i)].uv).transpose();
    b(i) = samples[static_cast<std::size_t>(i)].height;
  }
  if (ridge > 0) {  // ridge on the spline weights, scaled to the weights' columns
    const double lambda =
        options.spline_smoothing * A.block(0, 3, rows, ridge).squaredNorm() / static_cast<double>(ridge);
    for (Eigen::Index j = 0; j < ridge; ++j) A(rows + j, 3 + j) = std::sqrt(lambda);
  }
  m.coefficients = A.colPivHouseholderQr().solve(b);
  m.samples = samples.size();
  m.rms_mm = std::sqrt((A.topRows(rows) * m.coefficients - b.head(rows)).squaredNorm() / static_cast<double>(rows));
  return m;
}

}  // namespace conform
