#include "conform/toolpath/intersection/scan_quality.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "conform/core/error.h"
#include "conform/core/median.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/toolpath/intersection/local_quadric.h"

namespace conform {
namespace {

// Median edge length over (a stride sample of at most ~60000 of) the mesh's faces.
double median_edge(const Mesh& mesh) {
  std::vector<double> edges;
  const std::size_t stride = std::max<std::size_t>(1, mesh.faces.size() / 20000);
  for (std::size_t f = 0; f < mesh.faces.size(); f += stride) {
    for (int e = 0; e < 3; ++e) {
      const auto a = static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(e)]);
      const auto b = static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>((e + 1) % 3)]);
      edges.push_back((mesh.vertices[a] - mesh.vertices[b]).norm());
    }
  }
  return median(edges);
}

}  // namespace

ScanQuality estimate_scan_quality(const Mesh& mesh, const std::vector<Eigen::Vector3d>& points, int k,
                                  std::size_t max_samples) {
  if (k < 6) throw Error("scan quality: k must be >= 6");
  if (mesh.vertices.size() < static_cast<std::size_t>(k))
    throw Error("scan quality: the mesh has fewer than k vertices");
  ScanQuality quality;
  if (points.empty() || max_samples == 0) return quality;
  const KdTree tree(mesh.vertices);
  std::vector<double> noise;
  std::vector<double> curvature;
  const std::size_t stride = std::max<std::size_t>(1, points.size() / max_samples);
  for (std::size_t s = 0; s < points.size(); s += stride) {
    std::vector<int> indices;
    std::vector<float> sq;
    tree.knn(points[s].cast<float>(), k, indices, sq);
    std::vector<Eigen::Vector3d> q;
    for (const int i : indices) q.push_back(mesh.vertices[static_cast<std::size_t>(i)]);
    const LocalQuadric patch = fit_local_quadric(q, points[s]);
    double sum = 0.0;
    for (const Eigen::Vector3d& x : q) sum += patch.height(x) * patch.height(x);
    // The quadric has 6 parameters: the residual sum estimates (n - 6) sigma^2.
    noise.push_back(std::sqrt(sum / static_cast<double>(std::max<std::size_t>(1, q.size() - 6))));
    quality.normals.push_back(patch.gradient(points[s]).normalized());
    Eigen::Matrix2d hessian;
    hessian << 2.0 * patch.c[0], patch.c[1], patch.c[1], 2.0 * patch.c[2];
    const Eigen::Vector2d eigen = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(hessian).eigenvalues();
    curvature.push_back(std::max(std::abs(eigen(0)), std::abs(eigen(1))) / patch.scale);
  }
  quality.samples = noise.size();
  quality.noise_mm = median(noise);
  quality.edge_mm = median_edge(mesh);
  quality.curvature_per_mm = median(curvature);
  quality.edge_angle_deg = quality.edge_mm * quality.curvature_per_mm * 180.0 / 3.141592653589793;
  return quality;
}

double min_crossing_sine(const ScanQuality& a, const ScanQuality& b) {
  double smallest = 1.0;
  for (std::size_t i = 0; i < std::min(a.normals.size(), b.normals.size()); ++i) {
    smallest = std::min(smallest, a.normals[i].cross(b.normals[i]).norm());
  }
  return smallest;
}

}  // namespace conform
