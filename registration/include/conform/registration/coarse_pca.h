#pragma once
// Coarse alignment from the shapes' principal axes: the scan's centroid onto the reference's, its principal axes
// onto the reference's. The axes' signs are not determined by the data, so every proper combination is a start
// (4: two signs chosen, the third making a rotation); when two eigenvalues are nearly equal the axes in their plane
// are not determined either, and turns about the third axis are added. Rank the starts with multi_start.h.
// Works when scan and reference cover the same part of the surface (full overlap); use FPFH otherwise.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace conform {

struct PrincipalAxes {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();   // mm
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();   // unit columns, largest spread first, right-handed
  Eigen::Vector3d variances = Eigen::Vector3d::Zero();  // along each axis, mm^2, descending
};

// Throws conform::Error for fewer than 3 points.
PrincipalAxes principal_axes(const std::vector<Eigen::Vector3d>& points);

struct CoarseStart {
  std::string label;  // e.g. "pca +x+y", "pca -x+y turn 90", "fpfh", "identity"
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();
  // One of many fine candidates (a tube's turns about its axis, a few mm apart at its wall): rank_starts screens
  // these by a quick probe and probes only the best few (MultiStartOptions::wall_probes), as it does its wall shifts.
  bool screen = false;
};

// Two variances closer than `ambiguity` (relative to the larger) leave the axes in their plane free: the starts then
// include turns of 45 degrees about the remaining axis.
std::vector<CoarseStart> pca_starts(const std::vector<Eigen::Vector3d>& scan,
                                    const std::vector<Eigen::Vector3d>& reference, double ambiguity = 0.1);

}  // namespace conform
