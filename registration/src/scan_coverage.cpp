#include "scan_coverage.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>

#include <Eigen/Eigenvalues>

#include "conform/core/error.h"
#include "conform/registration/downsample.h"

namespace conform::detail {

namespace {

// A reference point is covered by a scan point within this many spacings.
constexpr double kCovered = 2.5;
// A scan point found marching round a point counts within this many spacings of the march's line.
constexpr double kHit = 1.5;
// Directions round a point that must each find scanned surface.
constexpr int kDirections = 8;
// A point farther than this many spacings from the scan is taken as off it (holes up to twice that across are seen);
// the march round a point goes twice as far (across such a hole from a point at its rim).
constexpr double kMaxGap = 40.0;
// A scan point is on the scan's rim (outer, or round a hole) when the centroid of its kRimNeighbours nearest lies
// more than kRimShift of the farthest one's distance away from it (a half disc's centroid: 0.42; a full disc's
// random sample's: mostly under 0.2).
constexpr int kRimNeighbours = 16;
constexpr double kRimShift = 0.3;
// Reference points within this many spacings of a rim point are tested first; the regions they find are then grown
// point by point.
constexpr double kSeedReach = 4.0;
// The tangent plane's tolerance grows by this share of the distance (a curved surface leaves its tangent plane).
constexpr double kCurvatureSlack = 0.1;
// A scan point found round a point is the same surface when its normal (over its kRimNeighbours) is within 45 deg of
// the point's: the surface the tangent plane allows for (kCurvatureSlack: a chord 6 deg off, the normal at its end 11
// deg) with room for noise. The rims of faces meeting the point's face at a step or an edge (their normals across
// it) do not count: a face the scanner did not see, bounded by scanned faces, is not a hole in the scan.
constexpr double kSameSurfaceCos = 0.7;

std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

ScanFootprint::ScanFootprint(const std::vector<Eigen::Vector3d>& scan, std::size_t max_points)
    : points_(stride_downsample(scan, max_points)), tree_(points_) {
  if (points_.size() <= 8) throw Error("scan footprint: fewer than 9 scan points");
  spacing_mm_ = std::sqrt(area_per_point(points_, tree_));
  for (const Eigen::Vector3d& p : points_) box_.extend(p);
  std::vector<char> rim(points_.size(), 0);
  normals_.assign(points_.size(), Eigen::Vector3d::Zero());
  const auto count = static_cast<std::ptrdiff_t>(points_.size());
#pragma omp parallel
  {
    std::vector<int> found;
    std::vector<float> sq;
#pragma omp for schedule(static)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      const auto i = static_cast<std::size_t>(k);
      tree_.knn(points_[i].cast<float>(), kRimNeighbours + 1, found, sq);  // the point itself first
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (std::size_t m = 1; m < found.size(); ++m) centroid += points_[static_cast<std::size_t>(found[m])];
      if (found.size() < 2) continue;
      centroid /= static_cast<double>(found.size() - 1);
      rim[i] = (centroid - points_[i]).norm() > kRimShift * std::sqrt(static_cast<double>(sq.back()));
      Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
      for (std::size_t m = 1; m < found.size(); ++m) {
        const Eigen::Vector3d e = points_[static_cast<std::size_t>(found[m])] - centroid;
        scatter += e * e.transpose();
      }
      normals_[i] = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(0);
    }
  }
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (rim[i]) rim_.push_back(i);
  }
}

bool ScanFootprint::hits(const Eigen::Vector3d& q, const Eigen::Vector3d& n, const Eigen::Vector3d& u, double to,
                         double sheet_mm) const {
  const double near = kHit * spacing_mm_;
  for (double t = 0.0; t <= to;) {
    const Eigen::Vector3d x = q + t * u;
    float sq = 0.0f;
    const int j = tree_.nearest(x.cast<float>(), &sq);
    if (j < 0) return false;
    const double d = std::sqrt(static_cast<double>(sq));
    const Eigen::Vector3d off = points_[static_cast<std::size_t>(j)] - q;
    if (d <= near && std::abs(off.dot(n)) <= sheet_mm + kCurvatureSlack * off.norm() &&
        std::abs(normals_[static_cast<std::size_t>(j)].dot(n)) >= kSameSurfaceCos) {
      return true;
    }
    t += std::max(d - near, spacing_mm_);  // nothing nearer than d - near to x lies on the line before that step
  }
  return false;
}

std::vector<Eigen::Vector3d> ScanFootprint::gaps(const IcpReference& reference, const Eigen::Isometry3d& T_ref_scan,
                                                 double sheet_mm, double link_mm,
                                                 double reference_area_mm2) const {
  const std::vector<Eigen::Vector3d>& points = reference.points();
  const std::vector<Eigen::Vector3d>& normals = reference.normals();
  if (normals.size() != points.size() || points.empty()) return {};
  const Eigen::Isometry3d to_scan = T_ref_scan.inverse();
  const double covered = kCovered * spacing_mm_, reach = kMaxGap * spacing_mm_;
  Eigen::AlignedBox3d box = box_;
  box.min().array() -= covered;
  box.max().array() += covered;
  // Whether reference point i is a gap.
  const auto is_gap = [&](std::size_t i) {
    const Eigen::Vector3d q = to_scan * points[i];
    if (!box.contains(q)) return false;
    float sq = 0.0f;
    const int j = tree_.nearest(q.cast<float>(), &sq);
    const double d = std::sqrt(static_cast<double>(sq));
    if (j < 0 || d <= covered || d > reach) return false;
    const Eigen::Vector3d n = to_scan.linear() * normals[i];
    // The nearest scan point lies on the point's tangent plane (a hole's rim; not the scanned face over a back face).
    const Eigen::Vector3d off = points_[static_cast<std::size_t>(j)] - q;
    if (std::abs(off.dot(n)) > sheet_mm + kCurvatureSlack * d) return false;
    // The first direction away from it: beyond the scan's rim that is where nothing is found, soonest.
    Eigen::Vector3d u = -(off - off.dot(n) * n);
    u = u.norm() > 0.0 ? Eigen::Vector3d(u.normalized()) : n.unitOrthogonal();
    const Eigen::Vector3d v = n.cross(u);
    for (int a = 0; a < kDirections; ++a) {
      const double angle = 2.0 * M_PI * a / kDirections;
      if (!hits(q, n, std::cos(angle) * u + std::sin(angle) * v, 2.0 * reach, sheet_mm)) return false;
    }
    return true;
  };
  // Seeds: the reference points near the scan's rims (a gap's nearest scan point is on the rim of the empty region it
  // lies in), then each seed's region grown point by point (within link_mm).
  std::vector<char> state(points.size(), 0);  // 0 untested, 1 tested and not a gap, 2 a gap, 3 a seed to test
  std::vector<int> found;
  std::vector<float> sq;
  std::vector<std::size_t> seeds;
  const double seed_reach = kSeedReach * spacing_mm_;
  // About one seed a squared scan spacing (a reference denser than the scan is thinned for the seeds), from every
  // other rim point (their spheres overlap 8-fold).
  const auto thin = static_cast<std::size_t>(
      std::max(1.0, std::floor(spacing_mm_ * spacing_mm_ / reference_area_mm2)));
  for (std::size_t k = 0; k < rim_.size(); k += 2) {
    const Eigen::Vector3d p = T_ref_scan * points_[rim_[k]];
    reference.tree().radius(p.cast<float>(), static_cast<float>(seed_reach), found, sq);
    for (const int f : found) {
      const auto m = static_cast<std::size_t>(f);
      if (state[m] == 0 && m % thin == 0) {
        state[m] = 3;
        seeds.push_back(m);
      }
    }
  }
  std::sort(seeds.begin(), seeds.end());
  const auto seed_count = static_cast<std::ptrdiff_t>(seeds.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t k = 0; k < seed_count; ++k) {
    const std::size_t i = seeds[static_cast<std::size_t>(k)];
    state[i] = is_gap(i) ? 2 : 1;
  }
  std::vector<std::size_t> queue;
  for (const std::size_t i : seeds) {
    if (state[i] == 2) queue.push_back(i);
  }
  while (!queue.empty()) {
    const std::size_t i = queue.back();
    queue.pop_back();
    reference.tree().radius(points[i].cast<float>(), static_cast<float>(link_mm), found, sq);
    for (const int f : found) {
      const auto m = static_cast<std::size_t>(f);
      if (state[m] != 0) continue;
      state[m] = is_gap(m) ? 2 : 1;
      if (state[m] == 2) queue.push_back(m);
    }
  }
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (state[i] == 2) out.push_back(to_scan * points[i]);
  }
  return out;
}

double area_per_point(const std::vector<Eigen::Vector3d>& points, const KdTree& tree) {
  constexpr int kNeighbours = 8;
  constexpr std::size_t kSamples = 500;
  if (points.size() <= kNeighbours) return 0.0;
  const std::size_t stride = std::max<std::size_t>(1, points.size() / kSamples);
  std::vector<double> r;
  std::vector<int> found;
  std::vector<float> sq;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    tree.knn(points[i].cast<float>(), kNeighbours + 1, found, sq);  // the point itself first
    r.push_back(std::sqrt(static_cast<double>(sq.back())));
  }
  std::nth_element(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(r.size() / 2), r.end());
  const double median = r[r.size() / 2];
  return M_PI * median * median / kNeighbours;
}

std::size_t largest_gap_only_here(const std::vector<Eigen::Vector3d>& gaps, const std::vector<Eigen::Vector3d>& others,
                                  double apart_mm, double link_mm) {
  std::vector<Eigen::Vector3d> here;
  if (others.empty()) {
    here = gaps;
  } else {
    const KdTree other_tree(others);
    for (const Eigen::Vector3d& g : gaps) {
      float sq = 0.0f;
      other_tree.nearest(g.cast<float>(), &sq);
      if (std::sqrt(static_cast<double>(sq)) > apart_mm) here.push_back(g);
    }
  }
  if (here.empty()) return 0;
  const KdTree tree(here);
  std::vector<std::size_t> parent(here.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  std::vector<int> found;
  std::vector<float> sq;
  for (std::size_t i = 0; i < here.size(); ++i) {
    tree.radius(here[i].cast<float>(), static_cast<float>(link_mm), found, sq);
    for (const int j : found) parent[root(parent, i)] = root(parent, static_cast<std::size_t>(j));
  }
  std::vector<std::size_t> size(here.size(), 0);
  for (std::size_t i = 0; i < here.size(); ++i) ++size[root(parent, i)];
  return *std::max_element(size.begin(), size.end());
}

GapComparison::GapComparison(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                             std::size_t scan_points, double sheet_mm)
    : scan_(scan),
      reference_(reference),
      scan_points_(scan_points),
      sheet_mm_(sheet_mm),
      area_per_point_(area_per_point(reference.points(), reference.tree())) {}

double GapComparison::scan_spacing_mm() {
  if (!footprint_) {
    footprint_.emplace(scan_, scan_points_);
    link_mm_ = 2.0 * std::max(footprint_->spacing_mm(), std::sqrt(area_per_point_));
  }
  return footprint_->spacing_mm();
}

const std::vector<Eigen::Vector3d>& GapComparison::gaps(const Eigen::Isometry3d& T) {
  scan_spacing_mm();  // the footprint and the link, once
  const Eigen::AlignedBox3d& box = footprint_->box();
  const double same = 0.5 * footprint_->spacing_mm();
  for (const auto& f : found_) {
    bool close = true;
    for (int c = 0; c < 8 && close; ++c) {
      const Eigen::Vector3d corner = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
      close = (T * corner - f.first * corner).norm() <= same;
    }
    if (close) return f.second;
  }
  found_.emplace_back(
      T, footprint_->gaps(reference_, T, std::max(sheet_mm_, footprint_->spacing_mm()), link_mm_, area_per_point_));
  return found_.back().second;
}

GapComparison::Regions GapComparison::compare(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b) {
  const std::vector<Eigen::Vector3d>& at_a = gaps(T_a);
  const std::vector<Eigen::Vector3d>& at_b = gaps(T_b);
  Regions r;
  r.a_only = largest_gap_only_here(at_a, at_b, link_mm_, link_mm_);
  r.b_only = largest_gap_only_here(at_b, at_a, link_mm_, link_mm_);
  return r;
}

}  // namespace conform::detail
