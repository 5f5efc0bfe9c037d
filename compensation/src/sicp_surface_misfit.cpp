#include "conform/compensation/sicp_surface_misfit.h"
#include "conform/core/constants.h"
#include "conform/core/median.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Dense>

#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

#include "path_closure.h"

namespace conform {
namespace {


// The path's direction at each row, from the rows before and after.
std::vector<Eigen::Vector3d> path_tangents(const std::vector<Eigen::Vector3d>& points, bool closed) {
  const std::size_t n = points.size();
  std::vector<Eigen::Vector3d> tangents(n, Eigen::Vector3d::Zero());
  for (std::size_t i = 0; n >= 2 && i < n; ++i) {
    const std::size_t next = i + 1 < n ? i + 1 : (closed ? 0 : n - 1);
    const std::size_t previous = i > 0 ? i - 1 : (closed ? n - 1 : 0);
    tangents[i] = points[next] - points[previous];
  }
  return tangents;
}

struct PointResidual {
  double residual_mm = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  bool found = false;
};

// Each scan point near the path, its residual against the model at the nearest row (once per point, not per row:
// the rows' discs overlap).
std::vector<PointResidual> residuals_near_path(const Trajectory& t, const std::vector<Eigen::Vector3d>& scan,
                                               const SicpModelResidual& residual, double radius_mm) {
  const KdTree rows(t.points);
  std::vector<PointResidual> out(scan.size());
  const auto r2 = static_cast<float>(radius_mm * radius_mm);
  for (std::size_t k = 0; k < scan.size(); ++k) {
    float sq = 0.0f;
    const int row = rows.nearest(scan[k].cast<float>(), &sq);
    if (row < 0 || sq > r2) continue;
    PointResidual& p = out[k];
    p.found = residual(scan[k], static_cast<std::size_t>(row), p.residual_mm, p.normal);
  }
  return out;
}

// Each row's local mean residual against its neighbours': the mean of the rows neighbour_from_mm to neighbour_to_mm
// along the path before it and after it (those with a mean), the two sides averaged (one alone at an open end). The
// neighbours' discs overlap: they count as independent every 2 near_radius_mm.
void compare_with_neighbours(const std::vector<Eigen::Vector3d>& points, bool closed, const SicpMisfitOptions& o,
                             const std::vector<double>& mean, std::vector<SicpRowMisfit>& m) {
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (m[i].near_points == 0) continue;
    double sides = 0.0, baseline = 0.0;
    for (int direction : {-1, 1}) {
      double d = 0.0, sum = 0.0;
      std::size_t count = 0, j = i;
      for (std::size_t steps = 1; steps < n; ++steps) {
        if (!closed && ((direction < 0 && j == 0) || (direction > 0 && j + 1 == n))) break;
        const std::size_t next = direction > 0 ? (j + 1) % n : (j + n - 1) % n;
        d += (points[next] - points[j]).norm();
        j = next;
        if (d > o.neighbour_to_mm || j == i) break;
        if (d >= o.neighbour_from_mm && m[j].near_points > 0) sum += mean[j], ++count;
      }
      if (count > 0) baseline += sum / static_cast<double>(count), sides += 1.0;
    }
    if (sides == 0.0) continue;
    const double independent =
        std::max(1.0, sides * (o.neighbour_to_mm - o.neighbour_from_mm) / (2.0 * o.near_radius_mm));
    m[i].local_offset_mm = mean[i] - baseline / sides;
    m[i].local_offset_se_mm *= std::sqrt(1.0 + 1.0 / independent);
  }
}


// The matched filter for a narrow dent (sicp_surface_misfit.h): the residuals (u, v, r) fitted by
// r = a + b u + c v + d u^2 + e u v + f v^2 + k g(u, v), g the Gaussian bump of sigma at the row; three passes, each
// without the residuals beyond 4 robust sigmas (at least 4 noise) of the fit before (the first: 3 mm off the median;
// the normal equations are updated by the points that leave or rejoin). Sets dent_mm, dent_z (|k| / se(k) from the
// noise, or from the fit's own robust scatter where that is larger: a misfit the background does not follow) and
// dent_slope_deg; leaves them 0 when the fit is ill-posed.
void fit_dent_bump(const std::vector<Eigen::Vector3d>& uvr, double sigma, double noise, std::size_t min_points,
                   SicpRowMisfit& m) {
  using Vector7d = Eigen::Matrix<double, 7, 1>;
  using Matrix7d = Eigen::Matrix<double, 7, 7>;
  const std::size_t enough = std::max<std::size_t>(min_points, 14);
  if (uvr.size() < enough) return;
  const double scale = 1.0 / (2.0 * sigma * sigma);
  std::vector<Vector7d> rows(uvr.size());
  std::vector<double> misfit(uvr.size()), deviation(uvr.size());
  std::vector<char> in(uvr.size(), 0);
  for (std::size_t k = 0; k < uvr.size(); ++k) {
    const Eigen::Vector3d& p = uvr[k];
    rows[k] << 1.0, p.x(), p.y(), p.x() * p.x(), p.x() * p.y(), p.y() * p.y(),
        std::exp(-p.head<2>().squaredNorm() * scale);
    misfit[k] = p.z();
  }
  double centre = median(misfit), limit = 3.0, spread = 0.0;
  Matrix7d XtX = Matrix7d::Zero();
  Vector7d Xtr = Vector7d::Zero();
  std::size_t used = 0;
  for (int pass = 0; pass < 3; ++pass) {
    for (std::size_t k = 0; k < uvr.size(); ++k) {
      const bool keep = std::abs(misfit[k] - centre) <= limit;
      if (keep == (in[k] != 0)) continue;
      const double sign = keep ? 1.0 : -1.0;
      XtX.noalias() += sign * rows[k] * rows[k].transpose();
      Xtr += sign * uvr[k].z() * rows[k];
      in[k] = keep ? 1 : 0;
      used = keep ? used + 1 : used - 1;
    }
    if (used < enough) return;
    const Eigen::LDLT<Matrix7d> ldlt(XtX);
    if (ldlt.info() != Eigen::Success || ldlt.vectorD().minCoeff() <= 1e-12 * XtX(0, 0)) return;
    const Vector7d fit = ldlt.solve(Xtr);
    const double variance = ldlt.solve(Vector7d::Unit(6))(6);
    if (!(variance > 0.0)) return;
    m.dent_mm = fit(6);
    m.dent_z = std::abs(fit(6)) / (std::max(noise, spread) * std::sqrt(variance));
    m.dent_slope_deg = std::atan(std::abs(fit(6)) * std::exp(-0.5) / sigma) * kDegPerRad;
    if (pass == 2) break;
    for (std::size_t k = 0; k < uvr.size(); ++k) {
      misfit[k] = uvr[k].z() - rows[k].dot(fit);
      deviation[k] = std::abs(misfit[k]);
    }
    centre = 0.0;
    spread = 1.4826 * median(deviation);
    limit = std::max(4.0 * spread, 4.0 * noise);
  }
}

}  // namespace

bool SicpMisfitOptions::IsValid(std::string* error) const {
  const char* why = nullptr;
  if (!std::isfinite(radius_mm) || radius_mm <= 0.0)
    why = "surface misfit radius must be > 0 mm";
  else if (min_points < 3)
    why = "surface misfit needs at least 3 points";
  else if (!std::isfinite(face_angle_deg) || face_angle_deg <= 0.0 || face_angle_deg >= 90.0)
    why = "face angle must be in (0, 90) deg";
  else if (!std::isfinite(near_radius_mm) || near_radius_mm <= 0.0 || near_radius_mm > radius_mm)
    why = "the local mean's radius must be in (0, surface misfit radius] mm";
  else if (!std::isfinite(neighbour_from_mm) || !std::isfinite(neighbour_to_mm) || neighbour_from_mm < 0.0 ||
           neighbour_to_mm <= neighbour_from_mm)
    why = "the neighbours' reach must satisfy 0 <= from < to mm";
  else if (!std::isfinite(dent_sigma_mm) || dent_sigma_mm <= 0.0)
    why = "the dent's sigma must be > 0 mm";
  else if (!std::isfinite(dent_radius_mm) || dent_radius_mm < 2.0 * dent_sigma_mm || dent_radius_mm > 100.0)
    why = "the dent fit's radius must be in [2 dent sigma, 100] mm";
  if (why == nullptr) return true;
  if (error != nullptr) *error = why;
  return false;
}

std::vector<SicpRowMisfit> sicp_surface_misfit(const Trajectory& t, const std::vector<Eigen::Vector3d>& predicted,
                                               const std::vector<Eigen::Vector3d>& scan, const KdTree& scan_tree,
                                               double noise_mm, const SicpModelResidual& residual,
                                               const SicpMisfitOptions& o) {
  std::string why;
  if (!o.IsValid(&why)) throw Error("S-ICP surface misfit: " + why);
  if (t.normals.size() != t.points.size() || predicted.size() != t.points.size())
    throw Error("S-ICP surface misfit: one tool normal per row needed");
  if (scan_tree.size() != scan.size()) throw Error("S-ICP surface misfit: the scan's index differs from the scan");
  std::vector<SicpRowMisfit> out(t.points.size());
  if (t.points.empty() || scan.empty()) return out;
  const double dent_radius = o.dent_radius_mm;
  const std::vector<PointResidual> r =
      residuals_near_path(t, scan, residual, std::max(o.radius_mm, dent_radius));
  const bool closed = detail::rows_close(t.points);
  const std::vector<Eigen::Vector3d> tangents = path_tangents(t.points, closed);
  const double face = std::cos(o.face_angle_deg / kDegPerRad);
  const double flank_sin = std::sin(30.0 / kDegPerRad);  // |cos| of the angle to the tool axis: within 30 deg of 90
  const double noise = std::max(noise_mm, 1e-6);
  const float plane_sq = static_cast<float>(o.radius_mm) * static_cast<float>(o.radius_mm);  // as the tree compares
  const float wide_sq = static_cast<float>(dent_radius) * static_cast<float>(dent_radius);
  const double wider = std::min(2.0 * o.radius_mm, std::max(o.radius_mm, dent_radius));
  const float wider_sq = static_cast<float>(wider) * static_cast<float>(wider);
  std::vector<std::pair<Eigen::Vector3d, float>> face_points;  // on the face within `wider`, with squared distance
  std::vector<double> near_mean(t.points.size(), 0.0);
  std::vector<int> indices;
  std::vector<float> sq;
  std::vector<Eigen::Vector3d> uvr, wide;  // along, across, residual: within radius_mm, within dent_radius_mm
  std::vector<double> values;
  for (std::size_t i = 0; i < t.points.size(); ++i) {
    const Eigen::Vector3d axis = t.normals[i].normalized();
    Eigen::Vector3d along = tangents[i] - tangents[i].dot(axis) * axis;
    if (along.norm() < 1e-12) continue;
    along.normalize();
    const Eigen::Vector3d across = axis.cross(along);
    scan_tree.radius(t.points[i].cast<float>(), static_cast<float>(std::max(o.radius_mm, dent_radius)), indices,
                     sq);
    wide.clear();
    face_points.clear();
    std::size_t flank = 0;
    for (std::size_t j = 0; j < indices.size(); ++j) {
      const PointResidual& p = r[static_cast<std::size_t>(indices[j])];
      if (p.found && sq[j] <= plane_sq && std::abs(p.normal.dot(axis)) < flank_sin) ++flank;
      if (!p.found || p.normal.dot(axis) < face) continue;
      const Eigen::Vector3d d = scan[static_cast<std::size_t>(indices[j])] - t.points[i];
      const Eigen::Vector3d point(d.dot(along), d.dot(across), p.residual_mm);
      if (sq[j] <= wide_sq) wide.push_back(point);
      if (sq[j] <= wider_sq) face_points.push_back({point, sq[j]});
    }
    SicpRowMisfit& m = out[i];
    m.flank_points = flank;
    fit_dent_bump(wide, o.dent_sigma_mm, noise, o.min_points, m);
    // The plane r = a + b u + c v through the face's points within `within` (squared, mm^2); false when they do not
    // fix one.
    const auto fit_plane = [&](float within) {
      uvr.clear();
      values.clear();
      for (const auto& [point, d2] : face_points) {
        if (d2 > within) continue;
        uvr.push_back(point);
        values.push_back(point.z());
      }
      if (uvr.size() < o.min_points) return false;
      const double centre = median(values);
      for (double& v : values) v = std::abs(v - centre);
      const double limit = std::max(4.0 * 1.4826 * median(values), 4.0 * noise);
      Eigen::Matrix3d XtX = Eigen::Matrix3d::Zero();
      Eigen::Vector3d Xtr = Eigen::Vector3d::Zero();
      std::size_t used = 0, near = 0;
      double near_sum = 0.0;
      for (const Eigen::Vector3d& p : uvr) {
        if (std::abs(p.z() - centre) > limit) continue;
        if (p.head<2>().squaredNorm() <= o.near_radius_mm * o.near_radius_mm) near_sum += p.z(), ++near;
        const Eigen::Vector3d x(1.0, p.x(), p.y());
        XtX += x * x.transpose();
        Xtr += x * p.z();
        ++used;
      }
      if (used < o.min_points || XtX.determinant() <= 1e-9 * std::pow(XtX(0, 0), 3)) return false;
      const Eigen::LDLT<Eigen::Matrix3d> ldlt(XtX);
      const Eigen::Vector3d fit = ldlt.solve(Xtr);
      const Eigen::Matrix3d cov = noise * noise * ldlt.solve(Eigen::Matrix3d::Identity());
      m.points = used;
      m.offset_mm = fit(0);
      m.offset_se_mm = std::sqrt(std::max(cov(0, 0), 0.0));
      // The surface h = a + b u + c v along the normal: its normal tilts by -(b, c); so should the tool normal.
      const Eigen::Vector3d expected = (predicted[i] - fit(1) * along - fit(2) * across).normalized();
      const Eigen::Vector3d difference = axis - expected;
      m.normal_error_deg = std::acos(std::clamp(expected.dot(axis), -1.0, 1.0)) * kDegPerRad;
      m.along_error_deg = std::abs(std::asin(std::clamp(difference.dot(along), -1.0, 1.0))) * kDegPerRad;
      m.across_error_deg = std::abs(std::asin(std::clamp(difference.dot(across), -1.0, 1.0))) * kDegPerRad;
      m.along_z = std::abs(fit(1)) / std::sqrt(std::max(cov(1, 1), 1e-30));
      m.across_z = std::abs(fit(2)) / std::sqrt(std::max(cov(2, 2), 1e-30));
      if (near >= 5) {
        m.near_points = near;
        near_mean[i] = near_sum / static_cast<double>(near);
        m.local_offset_se_mm = noise / std::sqrt(static_cast<double>(near));
      }
      return true;
    };
    // Within radius_mm; where those points do not fix a plane (laser stripes: one stripe crossing the disc is a
    // line), within twice that, so that a row between stripes is still checked.
    if (!fit_plane(plane_sq)) fit_plane(wider_sq);
  }
  compare_with_neighbours(t.points, closed, o, near_mean, out);
  return out;
}

}  // namespace conform
