#include "conform/registration/thin_walls.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "conform/core/error.h"
#include "conform/core/median.h"
#include "conform/registration/downsample.h"

namespace conform {

namespace {

// The far face is found when the line's point lies within this many spacings of its plane and the nearest reference
// point within kFarReach spacings of it (on random samples the nearest point is about half a spacing away).
constexpr double kPlaneSpacings = 0.75;
constexpr double kFarReach = 3.0;
// The search starts this many spacings off the near face: its own points are farther than that from the line.
constexpr double kFirstStep = 2.0;
// Thicknesses within this many spacings of the previous one sorted belong to one wall.
constexpr double kGroupSpacings = 2.0;

// The distance along `normal` from `p` to the first parallel face of the reference, 0 when none within `reach`.
double far_face(const IcpReference& reference, const Eigen::Vector3d& p, const Eigen::Vector3d& normal, double spacing,
                double reach, double min_cos) {
  // Steps are skipped as in sphere tracing: with no reference point within r of a step's point, no point is within
  // kFarReach spacings of the line before it has gone r - kFarReach spacings on, so none of the steps in between can
  // find the face (the same steps are found as by querying every one; the open side of a wall costs a few queries).
  double skip_to = 0.0;
  for (double d = kFirstStep * spacing; d <= reach + 0.5 * spacing; d += spacing) {
    if (d < skip_to) continue;
    const Eigen::Vector3d m = p + d * normal;
    const int j = reference.tree().nearest(m.cast<float>());
    if (j < 0) return 0.0;
    const auto k = static_cast<std::size_t>(j);
    const Eigen::Vector3d& q = reference.points()[k];
    const Eigen::Vector3d& nq = reference.normals()[k];
    const double r = (m - q).norm();
    if (std::abs((m - q).dot(nq)) <= kPlaneSpacings * spacing && r <= kFarReach * spacing &&
        std::abs(nq.dot(normal)) >= min_cos) {
      const double t = (q - p).dot(normal);
      return t <= reach ? t : 0.0;
    }
    // 0.999: a step that lies at the bound to within the tree's float rounding is still queried.
    skip_to = d + 0.999 * (r - kFarReach * spacing);
  }
  return 0.0;
}

// The principal directions of the unit vectors' scatter (sign-free) that hold at least `min_share` of it.
std::vector<Eigen::Vector3d> principal_directions(const std::vector<Eigen::Vector3d>& normals, double min_share) {
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& n : normals) scatter += n * n.transpose();
  scatter /= static_cast<double>(normals.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  std::vector<Eigen::Vector3d> out;
  for (int k = 2; k >= 0; --k) {  // ascending eigenvalues: largest first
    if (eig.eigenvalues()(k) >= min_share) out.push_back(eig.eigenvectors().col(k));
  }
  return out;
}

}  // namespace

std::vector<ThinWall> thin_walls(const IcpReference& reference, const ThinWallOptions& options) {
  if (!(options.max_thickness_mm > 0.0) || !std::isfinite(options.max_thickness_mm) || options.samples == 0 ||
      !(options.parallel_deg >= 0.0 && options.parallel_deg < 90.0) || !(options.min_share > 0.0) ||
      !(options.min_direction_share >= 0.0)) {
    throw Error("thin walls: max_thickness_mm must be finite and > 0, samples > 0, parallel_deg in [0, 90), "
                "min_share > 0 and min_direction_share >= 0");
  }
  std::vector<ThinWall> out;
  const std::vector<Eigen::Vector3d>& points = reference.points();
  const double spacing = median_spacing(points, reference.tree());
  if (!(spacing > 0.0) || reference.normals().size() != points.size()) return out;
  const double min_cos = std::cos(options.parallel_deg * M_PI / 180.0);
  const std::size_t n = points.size(), count = std::min(n, options.samples);
  struct Found {
    double thickness;
    Eigen::Vector3d normal;
  };
  std::vector<Found> found;
  for (std::size_t s = 0; s < count; ++s) {
    const std::size_t i = s * n / count;
    const Eigen::Vector3d& normal = reference.normals()[i];
    if (!(normal.squaredNorm() > 0.5)) continue;
    // The nearer of the two sides: a face's own normal may point either way on a cloud.
    double best = 0.0;
    for (const double sign : {1.0, -1.0}) {
      const double t = far_face(reference, points[i], sign * normal, spacing, options.max_thickness_mm, min_cos);
      if (t > 0.0 && (best == 0.0 || t < best)) best = t;
    }
    if (best > 0.0) found.push_back({best, normal});
  }
  // Stable: the same input gives the same groups in the same order, so the same directions to the last bit.
  std::stable_sort(found.begin(), found.end(),
                   [](const Found& a, const Found& b) { return a.thickness < b.thickness; });
  for (std::size_t first = 0; first < found.size();) {
    std::size_t last = first + 1;
    while (last < found.size() && found[last].thickness - found[last - 1].thickness <= kGroupSpacings * spacing) {
      ++last;
    }
    const double share = static_cast<double>(last - first) / static_cast<double>(count);
    if (share >= options.min_share) {
      ThinWall wall;
      std::vector<double> thicknesses;
      std::vector<Eigen::Vector3d> normals;
      for (std::size_t k = first; k < last; ++k) {
        thicknesses.push_back(found[k].thickness);
        normals.push_back(found[k].normal);
      }
      wall.thickness_mm = median(thicknesses);
      wall.share = share;
      wall.directions = principal_directions(normals, options.min_direction_share);
      out.push_back(wall);
    }
    first = last;
  }
  std::stable_sort(out.begin(), out.end(), [](const ThinWall& a, const ThinWall& b) { return a.share > b.share; });
  if (out.size() > options.max_walls) out.resize(options.max_walls);
  return out;
}

}  // namespace conform
