#include "conform/core/normals.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

namespace conform {

namespace {

// A neighbourhood counts as collinear when its second eigenvalue is below this fraction of the largest, i.e. its
// sideways spread is under 1e-6 of its length: the plane through it is then undetermined.
constexpr double kCollinear = 1e-12;
// A neighbourhood counts as round enough for the closed-form eigensolver when l1 >= kRound l2 (pca_normal).
constexpr double kRound = 0.05;

struct PcaNormal {
  Eigen::Vector3d normal;
  double curvature;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();  // of the neighbourhood, mm
  double residual = 0.0;  // mean squared distance of the neighbourhood from its plane, l0 / count, mm^2
  bool plane = false;     // false for the degenerate cases below (no plane through the neighbourhood)
};

// The unit vector along v, or `fallback` when v has no length.
Eigen::Vector3d unit_or(const Eigen::Vector3d& v, const Eigen::Vector3d& fallback) {
  const double len = v.stableNorm();
  return len > 0.0 ? Eigen::Vector3d(v / len) : fallback;
}

// PCA normal of the points point_at(j), j in `neighbours`, turned so that n . reference >= 0.
// The covariance is built in two passes (mean, then centred outer products) so that a neighbourhood 1e4 mm from the
// origin keeps full precision. The closed form (computeDirect()) is tried first and kept when the neighbourhood is
// round (l1 >= kRound l2): there it agrees with the iterative SelfAdjointEigenSolver to 1e-15 and is cheaper (the
// iterative solver was 15 % of the normals' time; with the closed form they take 7 % less, docs/align.md "Speed").
// Its eigenvalues carry an error of ~1e-9 of the largest, so it loses the smallest eigenvector of an elongated
// neighbourhood (a scan line, a thin strip): 4.7e-5 rad instead of 3e-11 on normals_test's 1:1000 strip, and 90
// degrees off at 1:10000; those are solved again iteratively. At l1 >= kRound l2
// the closed form's error is below 1e-9 / kRound = 2e-8 rad, under the float output's resolution.
// Degenerate neighbourhoods have no plane; they get a defined, NaN-free answer with curvature 0:
//   all points coincide -> the unit reference direction;
//   collinear           -> the part of the reference direction perpendicular to the line, normalised;
// and, when that is zero as well, the solver's smallest eigenvector.
template <typename PointAt>
PcaNormal pca_normal(const std::vector<int>& neighbours, PointAt&& point_at, const Eigen::Vector3d& reference) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int j : neighbours) mean += point_at(j);
  mean /= static_cast<double>(neighbours.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int j : neighbours) {
    const Eigen::Vector3d d = point_at(j) - mean;
    covariance.noalias() += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(covariance);
  if (!(solver.eigenvalues()(1) >= kRound * solver.eigenvalues()(2))) solver.compute(covariance);
  // Eigenvalues come sorted ascending; rounding can leave the smallest slightly negative.
  const Eigen::Vector3d lambda = solver.eigenvalues().cwiseMax(0.0);
  const Eigen::Vector3d smallest = solver.eigenvectors().col(0);
  const double total = lambda.sum();

  PcaNormal out{smallest, 0.0, mean, 0.0, false};
  if (total <= 0.0) {
    out.normal = unit_or(reference, smallest);
  } else if (lambda(1) <= kCollinear * lambda(2)) {
    const Eigen::Vector3d line = solver.eigenvectors().col(2);
    out.normal = unit_or(reference - reference.dot(line) * line, smallest);
  } else {
    out.curvature = lambda(0) / total;  // surface variation, Pauly et al. 2002
    out.residual = lambda(0) / static_cast<double>(neighbours.size());
    out.plane = true;
  }
  if (out.normal.dot(reference) < 0.0) out.normal = -out.normal;
  return out;
}

// The tree over the points; its complaint (non-finite points) is re-raised naming estimate_normals.
template <typename Points>
KdTree tree_over(const Points& points) {
  try {
    return KdTree(points);
  } catch (const Error& e) {
    throw Error(std::string("estimate_normals: ") + e.what());
  }
}

// Calls fn(position, neighbours) for every point of the tree, in parallel and in the tree's leaf order: near points
// one after the other, so that each query finds the last one's tree nodes and points still in cache (on a randomly
// ordered 1M-point tube a Z-curve order of the queries took the normals from 5.0 s to 2.2 s, one thread; the leaf
// order is coherent the same way and needs no sort: docs/align.md, "Speed"). Neighbours are named by position
// (kPositions: read from the tree's own storage, contiguous) or by the caller's index, in the same order either way.
// Each point's result depends only on its own neighbourhood, so the output is the same for any number of threads. An
// exception inside the loop is carried out of the parallel region and rethrown.
template <bool kPositions, typename Fn>
void for_each_neighbourhood(int k, const KdTree& tree, Fn&& fn) {
  std::exception_ptr failure;
  const auto count = static_cast<std::ptrdiff_t>(tree.size());
#pragma omp parallel
  {
    std::vector<int> neighbours;
    std::vector<float> sq_distances;
#pragma omp for schedule(dynamic, 256)
    for (std::ptrdiff_t i = 0; i < count; ++i) {
      try {
        const auto position = static_cast<std::size_t>(i);
        if constexpr (kPositions) {
          tree.knn_positions(tree.point_at_position(position), k, neighbours, sq_distances);
        } else {
          tree.knn(tree.point_at_position(position), k, neighbours, sq_distances);
        }
        fn(position, neighbours);
      } catch (...) {
#pragma omp critical(conform_normals_failure)
        if (!failure) failure = std::current_exception();
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
}

// The flattest neighbourhood that holds each point (NormalOptions::flattest_neighbourhood; docs/align.md, "Normals
// at steps and creases"). A point whose own k neighbours straddle a step or crease fits a plane between its sides;
// a neighbour whose own neighbourhood lies on one side fits that side. Point p takes the plane of neighbour q when
// q's mean squared residual is below 1 / kFlatter of p's and p lies on q's plane within kOnPlane of q's residual std
// (plus kRoundingShare of p's own residual, so that an exact plane's points are on it despite rounding); among
// several such q the flattest. A straddled step many times the noise high makes the ratio hundreds or more; on a
// smooth noisy surface neighbours' residuals differ by sampling alone and rarely by 16 times. On a noise-free curved
// surface the residuals are the curvature's and a few points take a neighbour's plane, up to (its distance) / R off
// (normals_test: max 0.062 rad instead of 0.039 on R = 30 mm at 1.1 mm spacing; mean unchanged). Choosing the
// nearest qualifying neighbour, a ratio of 4 or 8, or requiring p's nearest six points on q's plane too measured
// worse on the crease of normals_test or on the ribbed plate.
constexpr double kFlatter = 16.0;
constexpr double kOnPlane = 3.0;
constexpr double kRoundingShare = 1e-4;

// For every position p (fits[p] over the positions neighbours[p * k ...]), the position whose fit p takes.
std::vector<std::uint32_t> flattest_neighbourhoods(const KdTree& tree, const std::vector<PcaNormal>& fits,
                                                   const std::vector<int>& neighbours, std::size_t k) {
  const auto count = static_cast<std::ptrdiff_t>(fits.size());
  std::vector<std::uint32_t> chosen(fits.size());
#pragma omp parallel for schedule(static, 1024)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const auto p = static_cast<std::size_t>(i);
    const PcaNormal& own = fits[p];
    chosen[p] = static_cast<std::uint32_t>(p);
    if (!own.plane) continue;
    const Eigen::Vector3d x = tree.point_at_position(p).cast<double>();
    const int* around = &neighbours[p * k];
    double best = own.residual / kFlatter;
    for (std::size_t j = 1; j < k; ++j) {  // j = 0 is p itself (or a duplicate of it)
      const auto q = static_cast<std::size_t>(around[j]);
      const PcaNormal& other = fits[q];
      if (q == p || !other.plane || !(other.residual < best)) continue;
      const double distance = other.normal.dot(x - other.mean);
      if (distance * distance > kOnPlane * kOnPlane * other.residual + kRoundingShare * own.residual) continue;
      best = other.residual;
      chosen[p] = static_cast<std::uint32_t>(q);
    }
  }
  return chosen;
}

}  // namespace

bool NormalOptions::IsValid(std::string* error) const {
  const auto fail = [error](std::string message) {
    if (error != nullptr) *error = std::move(message);
    return false;
  };
  if (k < 3) return fail("k = " + std::to_string(k) + ": at least 3 neighbours per point are needed to fit a plane");
  switch (orientation) {
    case NormalOrientation::kTowardsViewpoint:
      if (!viewpoint.allFinite()) return fail("viewpoint is not finite (NaN or Inf)");
      return true;
    case NormalOrientation::kAwayFromAxis:
    case NormalOrientation::kTowardsAxis:
      if (!axis_point.allFinite()) return fail("axis_point is not finite (NaN or Inf)");
      if (!axis_direction.allFinite() || !(axis_direction.stableNorm() > 0.0)) {
        return fail("axis_direction must be a finite, non-zero vector to orient normals by an axis");
      }
      return true;
  }
  return fail("orientation is not one of the NormalOrientation values");
}

pcl::PointCloud<pcl::Normal> estimate_normals(const Cloud& cloud, const NormalOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("estimate_normals: invalid options: " + why);
  if (cloud.size() < 3) {
    throw Error("estimate_normals: the cloud has " + std::to_string(cloud.size()) +
                " points; at least 3 are needed to fit a plane");
  }
  return estimate_normals(tree_over(cloud.points), options);
}

pcl::PointCloud<pcl::Normal> estimate_normals(const KdTree& tree, const NormalOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("estimate_normals: invalid options: " + why);
  if (tree.size() < 3) {
    throw Error("estimate_normals: the cloud has " + std::to_string(tree.size()) +
                " points; at least 3 are needed to fit a plane");
  }
  const Eigen::Vector3d axis = options.axis_direction.stableNormalized();
  // Direction the normal must not point against (NormalOrientation's comments).
  const auto reference_at = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    if (options.orientation == NormalOrientation::kTowardsViewpoint) return options.viewpoint - p;
    const Eigen::Vector3d from_axis_point = p - options.axis_point;
    const Eigen::Vector3d radial = from_axis_point - from_axis_point.dot(axis) * axis;
    return options.orientation == NormalOrientation::kAwayFromAxis ? radial : Eigen::Vector3d(-radial);
  };
  const auto point_at = [&](int position) -> Eigen::Vector3d {
    return tree.point_at_position(static_cast<std::size_t>(position)).cast<double>();
  };

  // Pass 1: each point's own PCA fit, in leaf order (the neighbour lists kept for pass 2).
  const std::size_t count = tree.size();
  const auto k = std::min(static_cast<std::size_t>(options.k), count);
  std::vector<PcaNormal> fits(count);
  std::vector<int> neighbourhoods(options.flattest_neighbourhood ? count * k : 0);
  for_each_neighbourhood<true>(options.k, tree, [&](std::size_t position, const std::vector<int>& neighbours) {
    const Eigen::Vector3d p = tree.point_at_position(position).cast<double>();
    fits[position] = pca_normal(neighbours, point_at, reference_at(p));
    if (options.flattest_neighbourhood) std::copy(neighbours.begin(), neighbours.end(), &neighbourhoods[position * k]);
  });
  // Pass 2: each point's normal from the flattest neighbourhood that holds it, turned to its own reference.
  std::vector<std::uint32_t> chosen;
  if (options.flattest_neighbourhood) chosen = flattest_neighbourhoods(tree, fits, neighbourhoods, k);
  pcl::PointCloud<pcl::Normal> normals;
  normals.resize(count);
  const std::vector<std::uint32_t>& index_at = tree.leaf_order();
#pragma omp parallel for schedule(static, 4096)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(count); ++i) {
    const auto position = static_cast<std::size_t>(i);
    const std::size_t source = chosen.empty() ? position : chosen[position];
    Eigen::Vector3d n = fits[source].normal;
    if (source != position && n.dot(reference_at(tree.point_at_position(position).cast<double>())) < 0.0) n = -n;
    const Eigen::Vector3f nf = n.cast<float>();
    normals[index_at[position]] = pcl::Normal(nf.x(), nf.y(), nf.z(), static_cast<float>(fits[source].curvature));
  }
  return normals;
}

std::vector<Eigen::Vector3d> estimate_normals(const Mesh& mesh, int k) {
  if (k < 3) {
    throw Error("estimate_normals: k = " + std::to_string(k) +
                ": at least 3 neighbours per vertex are needed to fit a plane");
  }
  check_consistent(mesh, "estimate_normals");
  if (mesh.vertices.size() < 3) {
    throw Error("estimate_normals: the mesh has " + std::to_string(mesh.vertices.size()) +
                " vertices; at least 3 are needed to fit a plane");
  }
  if (!mesh.has_faces()) {
    throw Error(
        "estimate_normals: the mesh has no faces to orient the normals by; estimate them on the points as a "
        "cloud, oriented towards a viewpoint or by an axis");
  }
  const std::vector<Eigen::Vector3d> face_normals = vertex_normals_from_faces(mesh);
  const KdTree tree = tree_over(mesh.vertices);
  const auto point_at = [&](int j) -> const Eigen::Vector3d& { return mesh.vertices[static_cast<std::size_t>(j)]; };

  std::vector<Eigen::Vector3d> normals(mesh.vertices.size());
  const std::vector<std::uint32_t>& index_at = tree.leaf_order();
  for_each_neighbourhood<false>(k, tree, [&](std::size_t position, const std::vector<int>& neighbours) {
    const std::size_t i = index_at[position];
    // A vertex without faces (or whose faces cancel) borrows the face normals of its neighbours.
    Eigen::Vector3d reference = face_normals[i];
    if (reference.isZero(0.0)) {
      for (int j : neighbours) reference += face_normals[static_cast<std::size_t>(j)];
    }
    normals[i] = pca_normal(neighbours, point_at, reference).normal;
  });
  return normals;
}

}  // namespace conform
