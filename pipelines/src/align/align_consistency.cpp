#include "align/align_consistency.h"

#include <algorithm>

#include "conform/core/geometry.h"
#include "conform/core/mesh.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/core/normals.h"
#include "conform/registration/downsample.h"

namespace conform::detail {

namespace {

// The reverse fit keeps the reference points within this many robust std of the forward fit's residuals (plus the
// scan's spacing) of a scan point at the pose found: the part the scan covers, with a margin for a pose that is
// off. Measured over seed streams 0-2 of the workpiece matrix (docs/measurements/real_pairs.md): at 3 the reverse
// fit saw little more than what the forward fit had paired and agreed with a wrong pose (1.6 mm off, accepted); at
// 10 the closest wrong pose's std is 3.1 times the residual noise; at 20, or with no crop, the reverse fit of a 38 %
// overlap bunny pair slides over what the scan did not see (1.8 and 12 times the accuracy asked).
constexpr double kCropStds = 10.0;
// The wider neighbourhood of the normal-model spread: 4 times IcpReference's 16, the range over which the minimum
// was seen to move (docs/align.md, "Constraint").
constexpr int kModelSpreadNeighbours = 64;

// The discrepancy of `other` (a pose of the scan) against the forward fit.
FitDiscrepancy discrepancy(const std::vector<Eigen::Vector3d>& scan, const IcpResult& forward,
                           const Eigen::Isometry3d& other) {
  FitDiscrepancy out;
  out.ran = true;
  out.T_ref_scan = other;
  const Eigen::Isometry3d D = forward.T_ref_scan * other.inverse();  // in the reference frame
  const Eigen::AngleAxisd turn(D.linear());
  const Eigen::Vector3d& centre = forward.degeneracy.centre;
  out.twist << turn.angle() * turn.axis(), D * centre - centre;
  out.largest_displacement_mm = largest_displacement(scan, forward.T_ref_scan, other);
  return out;
}

// The reference points within `reach` mm of a scan point at the forward pose; `scan_tree` indexes the scan in its
// own frame (the reference points are moved there, so no second tree is built).
std::vector<Eigen::Vector3d> covered_part(const KdTree& scan_tree, const IcpReference& reference,
                                          const Eigen::Isometry3d& T_ref_scan, double reach) {
  const Eigen::Isometry3d T_scan_ref = T_ref_scan.inverse();
  const std::vector<Eigen::Vector3d>& points = reference.points();
  std::vector<unsigned char> keep(points.size(), 0);
  const float reach_sq = static_cast<float>(reach * reach);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(points.size()); ++i) {
    float sq = 0.0F;
    scan_tree.nearest((T_scan_ref * points[static_cast<std::size_t>(i)]).cast<float>(), &sq);
    keep[static_cast<std::size_t>(i)] = sq <= reach_sq;
  }
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (keep[i] != 0) out.push_back(points[i]);
  }
  return out;
}

}  // namespace

FitDiscrepancy inverse_consistency(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                                   const IcpResult& forward, const IcpOptions& fine) {
  if (scan.size() < 3 || reference.size() < 3) return {};
  Mesh scan_cloud;
  scan_cloud.vertices = scan;
  const IcpReference target(scan_cloud);
  const double reach = kCropStds * forward.degeneracy.noise_mm + median_spacing(scan, target.tree());
  const std::vector<Eigen::Vector3d> source = covered_part(target.tree(), reference, forward.T_ref_scan, reach);
  if (source.size() < 3) return {};
  IcpOptions reverse = fine;
  reverse.estimate_overlap = true;  // the reference covers more of the part than the scan, as a rule
  reverse.progress = nullptr;
  const IcpResult back = icp(stride_downsample(source, std::max<std::size_t>(scan.size(), 1)), target,
                             forward.T_ref_scan.inverse(), reverse);
  if (!back.converged) return {};
  return discrepancy(scan, forward, back.T_ref_scan.inverse());
}

FitDiscrepancy normal_model_spread(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                                   const IcpResult& forward, const IcpOptions& fine) {
  if (reference.size() < 3) return {};
  NormalOptions options;
  options.k = kModelSpreadNeighbours;
  options.viewpoint = centroid(reference.points());
  const pcl::PointCloud<pcl::Normal> normals = estimate_normals(reference.tree(), options);
  Mesh wider;
  wider.vertices = reference.points();
  wider.normals.resize(normals.size());
  for (std::size_t i = 0; i < normals.size(); ++i) wider.normals[i] = normals[i].getNormalVector3fMap().cast<double>();
  const IcpReference model(wider);
  IcpOptions again = fine;
  again.progress = nullptr;
  const IcpResult r = icp(scan, model, forward.T_ref_scan, again);
  if (!r.converged) return {};
  return discrepancy(scan, forward, r.T_ref_scan);
}

void add_bias(const FitDiscrepancy& discrepancy, DegeneracyReport& degeneracy) {
  if (!discrepancy.ran) return;
  degeneracy.covariance += discrepancy.twist * discrepancy.twist.transpose();
  degeneracy.std = degeneracy.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
}

}  // namespace conform::detail
