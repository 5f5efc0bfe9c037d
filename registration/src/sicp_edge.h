#pragma once
// The edge a one-sided scan shows: where the scanned band ends at the opening. A scan that sees only the face of the
// panel (a laser line looking down, a handheld pass over the material side) has no flank: its points pair with the
// nominal face, which is the same surface wherever a segment slides across the edge, so a segment's ICP holds its
// place across the edge by the face's curvature alone (a curved, deformed panel: 1-4.7 mm off the path, trusted).
// The paper finds the scan's boundary points first (Béarée et al. 2010, section 2.1); here they are found by the
// angular gap of their neighbours in the tangent plane, kept where they face the opening (across the contour, away
// from the nominal material), and hung as a short flank below the face (the panel is solid there), so that the
// point-to-surface ICPs pair them with the nominal flank and measure the edge across.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "conform/core/polyline.h"
#include "conform/registration/icp_reference.h"

namespace conform::detail {

struct ScanEdge {
  std::vector<Eigen::Vector3d> boundary;  // where the face ends, ahead of each boundary point facing the opening
  std::vector<Eigen::Vector3d> hung;      // below each, at the flank depths, along the face's inner normal
  double radius_mm = 0.0;  // the neighbourhood that judges a point: the median distance of the 24th nearest
};

// scan: in place to within reach_mm of the contour (the coarse ICP's reach); nominal: the nominal surface with its
// flank. Boundary points are looked for within reach_mm of the contour. Deterministic (no randomness, fixed order).
ScanEdge find_scan_edge(const std::vector<Eigen::Vector3d>& scan, const Polyline& contour, const IcpReference& nominal,
                        double reach_mm);

}  // namespace conform::detail
