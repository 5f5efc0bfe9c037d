#pragma once
// Subdivision-ICP (Béarée, Dieulot & Rabaté 2010): where is each piece of a deformed part's contour? A rigid ICP of
// the contour's neighbourhood places the part as a whole; the contour is then cut into short, overlapping, nearly
// straight segments (contour_segments.h), each registered on its own with its neighbourhood and stability points,
// and all segment transforms are refined together (sicp_joint.h) so that neighbours agree on their overlaps.
//
//   IcpReference nominal(nominal_surface_mesh);             // the CAD surface around the contour
//   const SicpResult r = sicp_register(contour, &nominal, scan_points, SicpOptions{});
//   r.segments[k].T_scan_nominal                            // maps the nominal segment onto the deformed part
//
// With a nominal surface, the scan's points are registered onto it (point-to-surface, exact on the CAD triangles):
// the scan points over the contour's neighbourhood and, per segment, over the stability region, the nominal surface
// beyond the neighbourhood (up to stability_mm from the contour) that keeps a segment's rotation realistic where
// the scan near the contour is missing. Without a surface, the contour points themselves are registered to the scan
// point-to-point, as in the paper, segment by segment (no joint refinement: its data terms need a surface).

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/core/polyline.h"
#include "conform/core/progress.h"
#include "conform/registration/contour_segments.h"
#include "conform/registration/icp.h"
#include "conform/registration/sicp_joint.h"

namespace conform {

struct SicpOptions {
  ContourSegmentationOptions segmentation;
  double scan_voxel_mm = 1.0;      // the scan thinned to one point per voxel first; 0: every point
  double neighbourhood_mm = 10.0;  // the contour's neighbourhood: scan points this close to the contour (mm)
  double stability_mm = 30.0;      // stability region: beyond the neighbourhood, up to this far from the contour
  // The coarse rigid ICP's pair distance (the scan starts roughly in place). Its first pass pairs point-to-plane with
  // the surface's vertices (cheap at this distance), its second point-to-surface within max_distance_mm.
  double coarse_max_distance_mm = 20.0;
  double max_distance_mm = 5.0;                   // the segment ICPs' and the joint refinement's pair distance
  std::size_t coarse_points = 2000;               // points of the coarse rigid ICP, at most (even stride)
  std::size_t points_per_segment = 150;           // neighbourhood points per segment, at most (even stride)
  std::size_t stability_points_per_segment = 50;  // stability points per segment, at most
  int max_iterations = 30;  // per ICP (coarse and segments alike), in [1, 1000]; reaching it is no failure
  bool coarse_segment_pass = true;  // each segment's ICP first at coarse_max_distance_mm, then at max_distance_mm
  bool reselect = true;  // with a surface: each segment's scan selected again at its own pose, its ICP run again
  // With a surface: the scan's boundary points facing the opening (within neighbourhood_mm of the contour), hung as a
  // short flank below the face, join the scan (sicp_edge.h): a scan without the opening's flank then still measures
  // the edge across. A scan with its flank has no such boundary points.
  bool scan_edge = true;
  bool joint_refinement = true;
  SicpJointOptions joint;
  bool rigid_only = false;  // stop after the coarse rigid ICP and judge each segment at its pose (rigid, projection)
  ProgressFn progress;      // stages "sicp: coarse", "sicp: segments", "sicp: joint"

  bool IsValid(std::string* error) const;
};

struct SicpSegmentFit {
  Eigen::Isometry3d T_scan_nominal = Eigen::Isometry3d::Identity();  // p_scan = T * p_nominal
  IcpResult icp;                         // the segment's own ICP (T_ref_scan there is nominal <- scan or the inverse)
  std::size_t neighbourhood_points = 0;  // in the segment's ICP
  std::size_t stability_points = 0;
  double rms_mm = 0.0;             // of the segment's pairs at its final transform, those off the surface left out
  double off_surface_share = 0.0;  // of its pairs, the share off the surface (sicp_residuals)
  bool converged = false;  // its ICP converged
  bool usable = false;     // its ICP ran and is usable (icp_usable); otherwise it starts from the coarse pose
};

struct SicpResult {
  ContourSegmentation segmentation;
  IcpResult coarse;  // the rigid ICP of the whole neighbourhood
  Eigen::Isometry3d T_scan_nominal_rigid = Eigen::Isometry3d::Identity();
  std::vector<SicpSegmentFit> segments;
  SicpJointReport joint;
  std::size_t scan_points_used = 0;   // after thinning
  std::vector<Eigen::Vector3d> scan_edge;  // where the scan's face ends at the opening (scan_edge; scan frame)
  // Per segment, the scan points it was judged on (with a surface; also for rigid_only, at the rigid pose, whose
  // segments then hold that pose and the RMS of its pairs there, so that every model is checked stretch by stretch).
  std::vector<std::vector<Eigen::Vector3d>> segment_scan;
  double rms_mm = 0.0;                // over every segment's pairs
  bool converged = false;             // the coarse ICP is usable, and so was the joint refinement when it ran
  std::string termination;            // "converged", or why not
  std::vector<std::string> warnings;  // segments without enough scan data, ...
};

// A segment's residuals judged robustly: a residual is off the surface when it lies more than 4 robust sigmas
// (1.4826 x the median absolute deviation from the median), and more than 0.2 mm, from the median; the RMS is that of
// the others. Stray
// points (spikes, dust: a share of a percent) then leave the RMS at the noise; a dent or a fixture that the segment
// cannot follow shows as a larger share off the surface (compensation/sicp_checks.h judges it).
struct SicpResiduals {
  double rms_mm = 0.0;
  double off_surface_share = 0.0;
  double sum_sq = 0.0;    // of the residuals on the surface
  std::size_t count = 0;  // residuals on the surface
};
SicpResiduals sicp_residuals(std::vector<double> residuals_mm);

// One rule for every ICP of S-ICP: converged, or stopped at the iteration limit (SicpOptions::max_iterations) with a
// pose that the residual checks then judge; any other termination (too few pairs, ...) is a failure.
bool icp_usable(const IcpResult& result);

// contour: nominal, ordered. nominal_surface: the CAD surface around it (nullptr: contour-only, point-to-point).
// scan: points of the deformed part, mm, roughly in place (the coarse ICP pairs points within
// coarse_max_distance_mm). Throws conform::Error for invalid options, a bad contour, an empty or non-finite scan.
SicpResult sicp_register(const Polyline& contour, const IcpReference* nominal_surface,
                         const std::vector<Eigen::Vector3d>& scan, const SicpOptions& options);

}  // namespace conform
