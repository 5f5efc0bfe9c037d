#pragma once
// One ICP step's correspondences and the choice of the pairs that take part: the distance gate, trimming to the
// overlap fraction, and the robust kernel's weights.

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/registration/icp_options.h"
#include "conform/registration/icp_reference.h"
#include "pair_cache.h"

namespace conform::detail {

struct Pair {
  Eigen::Vector3d q = Eigen::Vector3d::Zero();            // the scan point in the reference frame
  Eigen::Vector3d target = Eigen::Vector3d::Zero();       // its reference point (or surface point)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();       // the reference's unit normal there
  Eigen::Vector3d scan_normal = Eigen::Vector3d::Zero();  // plane-to-plane: the scan's unit normal, reference frame
  double distance = 0.0;                                  // |q - target|, mm
  double residual = 0.0;                                  // the method's: distance, or n . (q - target)
  bool found = false;
};

// How pairs are made and which are kept.
struct PairRules {
  IcpMethod method = IcpMethod::kPointToPlane;
  double max_distance_mm = 0.0;
};

// The points in Z-curve order (z_order, core/geometry.h). ICP iterates on the scan in this order: consecutive points
// are near each other, so each step's searches and the reference data they find stay in cache (with the leaf-ordered
// reference data: docs/align.md, "Speed"). The result depends on the order only through rounding.
std::vector<Eigen::Vector3d> spatially_ordered(const std::vector<Eigen::Vector3d>& points);

// Pairs for every scan point at T_ref_scan (found = false beyond the distance). Parallel, order-independent.
// scan_normals: the scan's unit normals (scan frame), one per point, for plane-to-plane; empty otherwise.
// `cache` (reset for this scan and method): each point's search is reused from the last call while that is exact
// (pair_cache.h): the same pairs, without most of the searches.
void find_pairs(const std::vector<Eigen::Vector3d>& scan, const std::vector<Eigen::Vector3d>& scan_normals,
                const Eigen::Isometry3d& T_ref_scan, const IcpReference& reference, const PairRules& rules,
                std::vector<Pair>& pairs, PairCache* cache = nullptr);

// The found pairs kept after trimming to `overlap` x scan size (smallest distances first), ascending by index.
std::vector<std::size_t> select_inliers(const std::vector<Pair>& pairs, double overlap);

// Fractional ICP's overlap (Phillips, Liu & Tomasi 2007, Eq. (3)): the share f of the scan's N points, those with the
// smallest distances, that minimises FRMSD(f) = RMSD(f) / f^lambda, RMSD(f) the RMS distance of those f N pairs; f at
// least min_fraction (of N). Pairs beyond the overlap are far and few near it grow RMSD faster than f^lambda pays for
// them; a scan that lies wholly on the reference keeps (nearly) all. Then widened to keep every pair within 3 robust
// standard deviations (1.4826 x the median distance of those kept): the noise's own tail is not trimmed. 0 when no
// pair was found.
double fractional_overlap(const std::vector<Pair>& pairs, double min_fraction, double lambda);

// Robust weights of the inliers' residuals and their scale (0 for kNone): scale = max(1.4826 median |r|, floor).
// The weights use max(scale, widen_to_mm): ICP widens the kernel while it creeps (icp.cpp, kCreepKernelScale).
std::vector<double> robust_weights(const std::vector<Pair>& pairs, const std::vector<std::size_t>& inliers,
                                   RobustKernel kernel, double min_scale_mm, double* scale_mm,
                                   double widen_to_mm = 0.0);

// The inliers' noise: 1.4826 median |r|, the standard deviation of Gaussian residuals, robust to up to half of them
// being outliers; at least min_scale_mm (0 without inliers). along_normal: of n . (q - target) instead of the
// method's residual (point-to-point's Euclidean distance is mostly the reference's spacing, not noise).
double noise_scale(const std::vector<Pair>& pairs, const std::vector<std::size_t>& inliers, double min_scale_mm,
                   bool along_normal = false);

// RMS of the inliers' residuals (unweighted), mm.
double inlier_rms(const std::vector<Pair>& pairs, const std::vector<std::size_t>& inliers);

}  // namespace conform::detail
