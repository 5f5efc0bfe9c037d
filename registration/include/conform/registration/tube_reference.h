#pragma once
// A scanned tube's own frame (z along its axis, as `generate tube` and the tube-joint frames L and S use), from
// >= 3 markers whose positions are known in the tube frame (HandySCAN targets, punch marks; their order gives the
// correspondence), with the cylinder fit (fitting/cylinder.h) as a prior.
//
// Markers that span a plane fix all 6 degrees of freedom: the frame is their least-squares rigid fit (Horn's closed
// form, horn.h). The cylinder fit is then only a cross-check: on an oval or peaked tube, a fit to a patch can put the
// axis several mm off (a 1 % oval leg, 68 deg patch: 17.8 mm), and constraining the frame to it would drag the
// markers off their known places. Its disagreement with the markers' frame is reported. Only when the markers leave
// a rotation free (all nearly on one line) does the fit's axis fix the other 4 degrees of freedom and the markers the
// rotation about it and the shift along it (2D Procrustes, closed form); both axis signs are tried. Without markers,
// rotation about the axis and shift along it are free: azimuth 0 then points in an arbitrary direction and z = 0 is
// the foot of the points' centroid, and the result says so (`free_about_axis`).

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/fitting/cylinder.h"

namespace conform {

struct TubeReferenceOptions {
  CylinderFitOptions fit;               // the axis fit (threshold, radius bounds, axis prior, seed ...)
  double max_marker_residual_mm = 2.0;  // a marker farther than this from its known position fails the result
  // Markers whose second principal extent is below this fraction of their first are taken as one line: the rotation
  // about it is then fixed by the cylinder fit.
  double collinear_ratio = 0.02;

  bool IsValid(std::string* error) const;
};

struct TubeReferenceResult {
  bool ok = false;
  std::string termination = "not run";  // "ok", or why not (fit failed, a marker residual too large)
  Eigen::Isometry3d T_tube_scan = Eigen::Isometry3d::Identity();  // p_tube = T_tube_scan * p_scan
  CylinderFitResult fit;
  bool free_about_axis = true;              // no markers: rotation about and shift along the axis are not determined
  std::vector<double> marker_residuals_mm;  // |T_tube_scan * m_scan - m_tube| per marker
  double marker_rms_mm = 0.0;
  double marker_max_mm = 0.0;
  std::string method = "axis";            // "markers" (6-DOF, Horn), "axis + markers" (collinear markers), "axis"
  // The cylinder fit against the markers' frame ("markers" only; -1 when the fit failed): the angle between the
  // fitted axis and z, deg, and the fitted axis's distance from the z axis at the markers' mean height, mm.
  double axis_disagreement_deg = -1.0;
  double axis_offset_mm = -1.0;
};

// Throws conform::Error when the options are invalid, the marker lists differ in length, there are 1 or 2 markers
// (0 or >= 3 are needed), or the markers are degenerate (all on the axis, or coincident along it: the rotation is
// undetermined). The fit's own errors propagate (fitting/cylinder.h).
TubeReferenceResult tube_reference(const std::vector<Eigen::Vector3d>& points,
                                   const std::vector<Eigen::Vector3d>& normals,
                                   const std::vector<Eigen::Vector3d>& markers_scan,
                                   const std::vector<Eigen::Vector3d>& markers_tube,
                                   const TubeReferenceOptions& options = {});

// The closed-form part on its own: given the axis (a point and a unit direction, in the scan), the markers.
// Returns T_tube_scan and writes the residuals.
Eigen::Isometry3d tube_frame_from_markers(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis_direction,
                                          const std::vector<Eigen::Vector3d>& markers_scan,
                                          const std::vector<Eigen::Vector3d>& markers_tube,
                                          std::vector<double>* residuals_mm);

}  // namespace conform
