#include "sicp_edge.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <Eigen/Eigenvalues>

#include "conform/core/constants.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/registration/sicp_pairs.h"

namespace conform::detail {
namespace {

// Depths below the face at which a boundary point is hung: within the flank of any panel at least 2 mm thick.
constexpr double kFlankDepthsMm[] = {0.5, 1.0, 1.5, 2.0};
// A point is on the scan's boundary when its neighbours leave a gap of more than a quarter turn around it.
constexpr double kBoundaryGapRad = 0.5 * kPi;
// The neighbours that decide the gap: within the median distance of a point's 24th nearest (as many inside).
constexpr int kNeighbours = 24;
// Facing the opening: across the contour (the gap's middle within 60 deg of the contour's normal in the surface)...
constexpr double kMaxAlongCos = 0.5;
// ... and towards where the nominal surface ends: 3 mm out, the nominal surface is at least 1 mm farther than 3 mm
// in (a hole in the scan or a missing arc's border faces the material or runs across the edge).
constexpr double kProbeMm = 3.0;
constexpr double kEndsMm = 1.0;
constexpr double kMinOffsetRadii = 0.25;
constexpr double kMinCoverage = 0.25;
// How far below a boundary point the scan is looked for on the flank.
constexpr double kFlankProbeMm = 2.0;
// Half the strip of edge whose outermost points say where the face ends.
constexpr double kWindowMm = 4.0;

struct EdgePoint {
  bool found = false;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // the boundary point
  Eigen::Vector3d edge = Eigen::Vector3d::Zero();    // where the face ends, on the scan
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // the face's, outwards (as the nominal face)
  Eigen::Vector3d out = Eigen::Vector3d::Zero();     // in the face, across the edge, towards the opening
};

double distance_to(const IcpReference& nominal, const Eigen::Vector3d& x) {
  const ReferencePoint r = closest_on_reference(nominal, x, 4.0 * kProbeMm);
  return r.found ? (x - r.point).norm() : 4.0 * kProbeMm;
}

// The tangent of the contour at point j (the chord through its neighbours).
Eigen::Vector3d tangent_at(const Polyline& contour, std::size_t j) {
  const std::size_t n = contour.points.size();
  const std::size_t next = j + 1 < n ? j + 1 : (contour.closed ? 0 : j);
  const std::size_t previous = j > 0 ? j - 1 : (contour.closed ? n - 1 : j);
  const Eigen::Vector3d t = contour.points[next] - contour.points[previous];
  return t.norm() > 1e-12 ? Eigen::Vector3d(t.normalized()) : Eigen::Vector3d::Zero();
}

EdgePoint judge(const std::vector<Eigen::Vector3d>& scan, const std::vector<int>& neighbours, double radius,
                std::size_t i, const Polyline& contour, const KdTree& contour_tree, const IcpReference& nominal) {
  EdgePoint e;
  if (neighbours.size() < 8) return e;
  const Eigen::Vector3d& p = scan[i];
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int k : neighbours) centroid += scan[static_cast<std::size_t>(k)];
  centroid /= static_cast<double>(neighbours.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int k : neighbours) {
    const Eigen::Vector3d d = scan[static_cast<std::size_t>(k)] - centroid;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d n = solver.eigenvectors().col(0);
  const Eigen::Vector3d u = solver.eigenvectors().col(2), v = n.cross(u);
  std::vector<double> angles;
  for (int k : neighbours) {
    const Eigen::Vector3d d = scan[static_cast<std::size_t>(k)] - p;
    if (static_cast<std::size_t>(k) == i || d.norm() < 1e-9) continue;
    angles.push_back(std::atan2(d.dot(v), d.dot(u)));
  }
  if (angles.size() < 6) return e;
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + kTwoPi - angles.back(), middle = angles.back() + 0.5 * gap;
  for (std::size_t k = 1; k < angles.size(); ++k) {
    if (angles[k] - angles[k - 1] > gap) gap = angles[k] - angles[k - 1], middle = angles[k - 1] + 0.5 * gap;
  }
  if (gap <= kBoundaryGapRad) return e;
  // Towards the edge: away from the neighbours' centroid, in the tangent plane (steadier than the gap's middle).
  Eigen::Vector3d out = p - centroid;
  out -= out.dot(n) * n;
  // An interior point's centroid is off by about a tenth of the radius (random sampling, ~25 neighbours); one within
  // a spacing of the edge by a quarter of it or more (centroid_offset at x = r / 3).
  if (out.norm() < kMinOffsetRadii * radius || out.normalized().dot(std::cos(middle) * u + std::sin(middle) * v) < 0.5)
    return e;
  out.normalize();
  const auto j = static_cast<std::size_t>(contour_tree.nearest(p.cast<float>()));
  if (std::abs(out.dot(tangent_at(contour, j))) > kMaxAlongCos) return e;
  const Eigen::Vector3d& c = contour.points[j];
  if (distance_to(nominal, c + kProbeMm * out) < distance_to(nominal, c - kProbeMm * out) + kEndsMm) return e;
  // The nominal face's own normal beside the contour point (not at the scan's points, which the deformation may have
  // moved below the face, nor the direction to a point, which flips with the noise) orients the hung flank.
  const SurfacePoint face = nominal.surface().closest(c - kProbeMm * out, 4.0 * kProbeMm);
  if (!face.found()) return e;
  const Eigen::Vector3d face_normal = nominal.surface().normal_at(face);
  if (std::abs(face_normal.dot(n)) < 0.7) return e;  // not over the nominal face
  e.found = true;
  e.normal = face_normal.dot(n) >= 0.0 ? n : Eigen::Vector3d(-n);
  e.point = p;
  e.out = out;
  return e;
}

// Where the face ends, across the edge at each boundary point: the outermost scan points within kWindowMm (a strip of
// the edge 2 kWindowMm long) reach it but for the gap sampling leaves: under random sampling a gap g = 1 / (density x
// strip length) on average for the outermost, m g for the m-th (order statistics); the second outermost is taken,
// so that one stray point does not set it, moved out by 1.5 g (the strip is shorter where the edge curves). Each
// point's own centroid offset put the edge 0.08-0.28 mm inside, biased by the choice of the points; the spread of the
// four outermost as the gap's measure put the paths 0.28-0.35 mm off on a voxel-thinned scan, against 0.14-0.22 mm.
std::vector<EdgePoint> outermost(const std::vector<EdgePoint>& points, double density_per_mm2) {
  std::vector<Eigen::Vector3d> places;
  for (const EdgePoint& e : points) places.push_back(e.point);
  const KdTree tree(places);
  std::vector<EdgePoint> result = points;
  std::vector<int> indices;
  std::vector<float> sq;
  const double gap = 1.0 / (density_per_mm2 * 2.0 * kWindowMm);
  for (std::size_t i = 0; i < points.size(); ++i) {
    tree.radius(places[i].cast<float>(), static_cast<float>(kWindowMm), indices, sq);
    std::vector<double> ahead;
    for (int j : indices) {
      if (points[static_cast<std::size_t>(j)].out.dot(points[i].out) < 0.5) continue;  // another side of a corner
      ahead.push_back((places[static_cast<std::size_t>(j)] - places[i]).dot(points[i].out));
    }
    std::sort(ahead.begin(), ahead.end(), std::greater<>());
    const std::size_t m = ahead.size() >= 4 ? 2 : 1;
    result[i].edge = places[i] + (ahead[m - 1] + (static_cast<double>(m) - 0.5) * gap) * points[i].out;
  }
  // Then the mean across the edge over the same strip: one strip's outermost points scatter by about a gap.
  std::vector<EdgePoint> smooth = result;
  for (std::size_t i = 0; i < points.size(); ++i) {
    tree.radius(places[i].cast<float>(), static_cast<float>(kWindowMm), indices, sq);
    double sum = 0.0;
    std::size_t count = 0;
    for (int j : indices) {
      const EdgePoint& e = result[static_cast<std::size_t>(j)];
      if (e.out.dot(points[i].out) < 0.5) continue;
      sum += (e.edge - result[i].edge).dot(points[i].out);
      ++count;
    }
    smooth[i].edge += sum / static_cast<double>(std::max<std::size_t>(count, 1)) * points[i].out;
  }
  return smooth;
}

}  // namespace

ScanEdge find_scan_edge(const std::vector<Eigen::Vector3d>& scan, const Polyline& contour, const IcpReference& nominal,
                        double reach_mm) {
  ScanEdge edge;
  if (!nominal.has_surface() || scan.size() < 20 || contour.points.size() < 3) return edge;
  const KdTree contour_tree(contour.points);
  std::vector<std::size_t> near;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    float sq = 0.0f;
    contour_tree.nearest(scan[i].cast<float>(), &sq);
    if (static_cast<double>(sq) <= reach_mm * reach_mm) near.push_back(i);
  }
  if (near.size() < 20) return edge;
  const KdTree tree(scan);
  std::vector<double> gaps;
  std::vector<int> indices;
  std::vector<float> sq;
  const std::size_t samples = std::min<std::size_t>(near.size(), 500);
  for (std::size_t k = 0; k < samples; ++k) {
    tree.knn(scan[near[k * near.size() / samples]].cast<float>(), kNeighbours + 1, indices, sq);
    if (sq.size() == kNeighbours + 1) gaps.push_back(std::sqrt(static_cast<double>(sq.back())));
  }
  if (gaps.empty()) return edge;
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  edge.radius_mm = gaps[gaps.size() / 2];
  const auto radius = static_cast<float>(edge.radius_mm);
  std::vector<EdgePoint> judged(near.size());
  const auto count = static_cast<std::ptrdiff_t>(near.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    std::vector<int> neighbours;
    std::vector<float> distances;
    const std::size_t i = near[static_cast<std::size_t>(k)];
    tree.radius(scan[i].cast<float>(), radius, neighbours, distances);
    EdgePoint e = judge(scan, neighbours, radius, i, contour, contour_tree, nominal);
    // Nothing of the scan ahead: a disc of half the radius, just ahead of the point, holds about 6 points inside the
    // face and none beyond its end (interior points pass the gap and offset tests by chance, some in a thousand).
    if (e.found) {
      const Eigen::Vector3d ahead = e.point + 0.6 * edge.radius_mm * e.out;
      tree.radius(ahead.cast<float>(), 0.5f * radius, neighbours, distances);
      e.found = neighbours.empty();
    }
    // Nor below it: where the flank was scanned, the face's end is no edge of the scan (its points found by the
    // gap are the rim's, between face and flank) and the flank measures the edge itself.
    if (e.found) {
      const Eigen::Vector3d below = e.point - kFlankProbeMm * e.normal;
      tree.radius(below.cast<float>(), 0.35f * radius, neighbours, distances);
      e.found = neighbours.empty();
    }
    judged[static_cast<std::size_t>(k)] = e;
  }
  std::vector<EdgePoint> found;
  for (const EdgePoint& e : judged) {
    if (e.found) found.push_back(e);
  }
  // A scan with its flank, or without a clear end at the opening, shows a few scattered boundary points (noise,
  // corners): an edge is taken only where a quarter of the contour's length or more shows one (a one-sided scan of
  // the generated panels: 40-90%).
  const double spacing = edge.radius_mm / std::sqrt(kNeighbours / kPi);
  if (static_cast<double>(found.size()) < kMinCoverage * length(contour) / spacing) return edge;
  for (const EdgePoint& e : outermost(found, kNeighbours / (kPi * edge.radius_mm * edge.radius_mm))) {
    edge.boundary.push_back(e.edge);
    for (double depth : kFlankDepthsMm) edge.hung.push_back(e.edge - depth * e.normal);
  }
  return edge;
}

}  // namespace conform::detail
