#include "conform/evaluation/revolved_fit.h"

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "conform/core/constants.h"

namespace conform {

namespace {

constexpr double kStep = 1e-6;          // central-difference step, mm or rad
constexpr int kMaxIterations = 100;
constexpr double kMinConditioning = 1e-12;  // smallest / largest eigenvalue of the scaled normal equations

// The axis a tilted by (du, dv) along two directions perpendicular to it.
Eigen::Vector3d tilted(const Eigen::Vector3d& a, double du, double dv) {
  const Eigen::Vector3d u = a.unitOrthogonal(), v = a.cross(u);
  return (a + du * u + dv * v).normalized();
}

// Height along the axis and distance from it of q, for an axis through c along unit a.
Eigen::Vector2d height_and_radius(const Eigen::Vector3d& c, const Eigen::Vector3d& a, const Eigen::Vector3d& q) {
  const Eigen::Vector3d d = q - c;
  const double h = d.dot(a);
  return {h, (d - h * a).norm()};
}

struct ConeModel {
  static constexpr int kParameters = 6;
  Eigen::Vector3d c;  // axis point, relative to the centroid
  Eigen::Vector3d a;
  double r;
  double alpha;
  ConeModel moved(const Eigen::Matrix<double, 6, 1>& d) const {
    const Eigen::Vector3d u = a.unitOrthogonal(), v = a.cross(u);
    return {c + d(0) * u + d(1) * v, tilted(a, d(2), d(3)), r + d(4), alpha + d(5)};
  }
  double distance(const Eigen::Vector3d& q) const {
    const Eigen::Vector2d hr = height_and_radius(c, a, q);
    return (hr(1) - r - hr(0) * std::tan(alpha)) * std::cos(alpha);
  }
  bool valid() const { return r > 0.0 && alpha > 0.0 && alpha < kHalfPi && c.allFinite() && a.allFinite(); }
};

struct TorusModel {
  static constexpr int kParameters = 7;
  Eigen::Vector3d c;  // centre, relative to the centroid
  Eigen::Vector3d a;
  double major;
  double minor;
  TorusModel moved(const Eigen::Matrix<double, 7, 1>& d) const {
    return {c + d.head<3>(), tilted(a, d(3), d(4)), major + d(5), minor + d(6)};
  }
  double distance(const Eigen::Vector3d& q) const {
    const Eigen::Vector2d hr = height_and_radius(c, a, q);
    return std::hypot(hr(1) - major, hr(0)) - minor;
  }
  bool valid() const { return major > 0.0 && minor > 0.0 && c.allFinite() && a.allFinite(); }
};

template <class Model>
double cost_of(const Model& m, const std::vector<Eigen::Vector3d>& q) {
  double sum = 0.0;
  for (const Eigen::Vector3d& p : q) sum += std::pow(m.distance(p), 2);
  return sum;
}

struct Outcome {
  int iterations = 0;
  bool converged = false;
  bool conditioned = false;
  double cost = 0.0;
};

// Levenberg-Marquardt (Marquardt 1963: the diagonal of J^T J scaled by lambda) on the orthogonal distances, the
// Jacobian by central differences in the model's own local parameters.
template <class Model>
Outcome levenberg_marquardt(Model& model, const std::vector<Eigen::Vector3d>& q) {
  constexpr int P = Model::kParameters;
  using Vector = Eigen::Matrix<double, P, 1>;
  using Matrix = Eigen::Matrix<double, P, P>;
  Outcome out;
  out.cost = cost_of(model, q);
  double lambda = 1e-3;
  Matrix jtj = Matrix::Zero();
  for (; out.iterations < kMaxIterations && !out.converged; ++out.iterations) {
    jtj.setZero();
    Vector jtr = Vector::Zero();
    std::vector<Model> plus, minus;
    for (int k = 0; k < P; ++k) {
      Vector d = Vector::Zero();
      d(k) = kStep;
      plus.push_back(model.moved(d));
      minus.push_back(model.moved(-d));
    }
    for (const Eigen::Vector3d& p : q) {
      Vector j;
      for (int k = 0; k < P; ++k) j(k) = (plus[k].distance(p) - minus[k].distance(p)) / (2.0 * kStep);
      jtj += j * j.transpose();
      jtr += j * model.distance(p);
    }
    bool stepped = false;
    for (int tries = 0; tries < 12 && !stepped; ++tries) {
      Matrix damped = jtj;
      damped.diagonal() *= 1.0 + lambda;
      const Vector delta = damped.ldlt().solve(-jtr);
      if (!delta.allFinite()) break;
      const Model candidate = model.moved(delta);
      const double cost = candidate.valid() ? cost_of(candidate, q) : HUGE_VAL;
      if (cost <= out.cost) {
        stepped = true;
        out.converged = delta.norm() < 1e-10 || out.cost - cost <= 1e-14 * out.cost;
        model = candidate;
        out.cost = cost;
        lambda = std::max(lambda * 0.1, 1e-12);
      } else {
        lambda *= 10.0;
      }
    }
    if (!stepped) out.converged = true;  // no step lowers the cost: a minimum to the arithmetic's precision
  }
  // Well conditioned: the normal equations, scaled to a unit diagonal, are far from singular.
  const Vector scale = jtj.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Matrix scaled = scale.asDiagonal() * jtj * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix> eigen(scaled);
  const Vector values = eigen.eigenvalues();
  out.conditioned = values(P - 1) > 0.0 && values(0) > kMinConditioning * values(P - 1);
  return out;
}

Eigen::Vector3d centroid_of(const std::vector<Eigen::Vector3d>& points, std::vector<Eigen::Vector3d>& relative) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  relative.reserve(points.size());
  for (const Eigen::Vector3d& p : points) relative.push_back(p - centroid);
  return centroid;
}

}  // namespace

double cone_distance(const ConeFit& cone, const Eigen::Vector3d& p) {
  const ConeModel m{cone.axis_point, cone.axis, cone.radius_mm, cone.half_angle_rad};
  return m.distance(p);
}

ConeFit fit_cone(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& apex, const Eigen::Vector3d& axis,
                 double half_angle_rad) {
  ConeFit fit;
  if (points.size() < 7 || !(half_angle_rad > 0.0 && half_angle_rad < kHalfPi) || !(axis.norm() > 0.0)) return fit;
  std::vector<Eigen::Vector3d> q;
  const Eigen::Vector3d centroid = centroid_of(points, q);
  const Eigen::Vector3d a = axis.normalized();
  // The start: the nominal cone's axis point nearest the centroid, and its radius there.
  const double h = (centroid - apex).dot(a);
  ConeModel model{apex + h * a - centroid, a, h * std::tan(half_angle_rad), half_angle_rad};
  if (!model.valid()) return fit;
  const Outcome out = levenberg_marquardt(model, q);
  fit.axis_point = model.c + centroid;
  fit.axis = model.a;
  fit.radius_mm = model.r;
  fit.half_angle_rad = model.alpha;
  fit.apex = fit.axis_point - model.r / std::tan(model.alpha) * model.a;
  fit.rms_mm = std::sqrt(out.cost / static_cast<double>(q.size()));
  fit.iterations = out.iterations;
  fit.ok = out.converged && out.conditioned && model.valid() && std::isfinite(fit.rms_mm);
  return fit;
}

double torus_distance(const TorusFit& torus, const Eigen::Vector3d& p) {
  const TorusModel m{torus.centre, torus.axis, torus.major_radius_mm, torus.minor_radius_mm};
  return m.distance(p);
}

TorusFit fit_torus(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& axis, double major_radius_mm, double minor_radius_mm) {
  TorusFit fit;
  if (points.size() < 8 || !(axis.norm() > 0.0)) return fit;
  std::vector<Eigen::Vector3d> q;
  const Eigen::Vector3d centroid = centroid_of(points, q);
  TorusModel model{centre - centroid, axis.normalized(), major_radius_mm, minor_radius_mm};
  if (!model.valid()) return fit;
  const Outcome out = levenberg_marquardt(model, q);
  fit.centre = model.c + centroid;
  fit.axis = model.a;
  fit.major_radius_mm = model.major;
  fit.minor_radius_mm = model.minor;
  fit.rms_mm = std::sqrt(out.cost / static_cast<double>(q.size()));
  fit.iterations = out.iterations;
  fit.ok = out.converged && out.conditioned && model.valid() && std::isfinite(fit.rms_mm);
  return fit;
}

}  // namespace conform
