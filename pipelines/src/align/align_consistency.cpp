#include "align/align_consistency.h"

#include <algorithm>

#include "conform/core/mesh.h"
#include "conform/registration/downsample.h"
#include "conform/registration/icp_reference.h"

namespace conform::detail {

InverseConsistency inverse_consistency(const std::vector<Eigen::Vector3d>& scan,
                                       const std::vector<Eigen::Vector3d>& reference, const IcpResult& forward,
                                       const IcpOptions& fine) {
  InverseConsistency out;
  if (scan.empty() || reference.empty()) return out;
  Mesh scan_cloud;
  scan_cloud.vertices = scan;
  const IcpReference target(scan_cloud);
  IcpOptions reverse = fine;
  reverse.estimate_overlap = true;  // the reference covers more of the part than the scan, as a rule
  reverse.progress = nullptr;
  const IcpResult back = icp(stride_downsample(reference, std::max<std::size_t>(scan.size(), 1)), target,
                             forward.T_ref_scan.inverse(), reverse);
  if (!back.converged) return out;
  out.ran = true;
  out.T_ref_scan = back.T_ref_scan.inverse();
  const Eigen::Isometry3d D = forward.T_ref_scan * out.T_ref_scan.inverse();  // in the reference frame
  const Eigen::AngleAxisd turn(D.linear());
  const Eigen::Vector3d& centre = forward.degeneracy.centre;
  out.twist << turn.angle() * turn.axis(), D * centre - centre;
  for (const Eigen::Vector3d& p : scan) {
    out.largest_displacement_mm =
        std::max(out.largest_displacement_mm, (forward.T_ref_scan * p - out.T_ref_scan * p).norm());
  }
  return out;
}

void add_consistency_bias(const InverseConsistency& consistency, DegeneracyReport& degeneracy) {
  if (!consistency.ran) return;
  degeneracy.covariance += consistency.twist * consistency.twist.transpose();
  degeneracy.std = degeneracy.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
}

}  // namespace conform::detail
