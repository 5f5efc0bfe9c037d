#pragma once
// Does the path follow the scanned surface where it runs? A model's transforms follow the part at the scale of a
// segment (S-ICP: 40 mm) or of the whole part (rigid, projection); a local shape change shorter than that — a dent at
// the edge, a bulge — leaves the path off along the tool axis and its tool normals tilted, while the segment's RMS
// can stay near the noise (the segment tilts to follow the dent part way). So the residuals are judged by their
// structure at each row, against what the point count can resolve, not by their RMS against the noise:
//
//   - at each row, the scan points of the face within radius_mm of the compensated row (within twice that where
//     those do not fix a plane: laser stripes, one of which can be all the disc holds) (the model's normal there
//     within face_angle_deg of the row's tool axis: the flank and the rim are left out), their residuals against the
//     model's image of the nominal surface at that place, fitted by a plane r = a + b u + c v in the row's frame (u
//     along the path, v across it): a is where the scanned surface lies off the model's at the row (the path's error
//     along the tool axis), (b, c) its tilt (the tool normal's error);
//   - a dent narrower than the plane's disc (its slope smoothed away there: a 10 mm wide dent's 7 deg came out at
//     1.5-2 deg) by a matched filter: the residuals within dent_radius_mm fitted by a quadratic background (the
//     model's own smooth misfit) plus a Gaussian bump k exp(-(u^2 + v^2) / (2 dent_sigma_mm^2)) centred at the row;
//     the background is measured by the wider disc, so the bump's depth k keeps most of a narrow dent's signal. The
//     slope the bump implies at its steepest, atan(|k| e^-1/2 / dent_sigma_mm), is what the tool normal misses there.
//     Fitted three times, each time without the residuals beyond 4 robust sigmas (and 4 noise) of the fit (stray
//     points; the first time those 3 mm or more off the median); k's standard error from the noise or, where larger,
//     the fit's own robust scatter;
//   - the mean residual within near_radius_mm of the row against the same mean at the rows neighbour_from_mm to
//     neighbour_to_mm along the path on either side: a dent or bulge a few mm across stands out of its neighbours, the
//     model's own misfit, which varies over a segment's length, does not.
// Each figure has its standard error from the scan's noise and the points' layout ((X^T X)^-1 noise^2, noise /
// sqrt(n)), so that a check asks whether a figure is significant whatever the noise level. Residuals beyond 4 robust
// sigmas of the row's median (and 4 noise: stray points) are left out.
//
//   const auto misfit = sicp_surface_misfit(compensated, predicted_normals, scan, scan_tree, noise, residual, {});
//   misfit[i].offset_mm, misfit[i].along_error_deg, misfit[i].local_offset_mm  // judged by check_sicp_path

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/compensation/trajectory.h"

namespace conform {

class KdTree;

struct SicpMisfitOptions {
  double radius_mm = 6.0;          // scan points this close to the compensated row fit its plane, > 0
  std::size_t min_points = 12;     // fewer face points: the row is not fitted (its edge support judges it), >= 3
  double face_angle_deg = 30.0;    // a point whose model normal is within this of the row's tool axis is on the face
  double near_radius_mm = 4.0;     // the local mean residual: points this close to the row, in (0, radius_mm]
  double neighbour_from_mm = 8.0;  // ... against the rows this far along the path ...
  double neighbour_to_mm = 16.0;   // ... to this far, on either side, > neighbour_from_mm
  double dent_sigma_mm = 2.5;      // the bump's sigma: a quarter of the narrowest dent looked for (10 mm wide), > 0
  double dent_radius_mm = 18.0;    // the bump's fit: points this close to the row, in [2 dent_sigma_mm, 100]
  bool IsValid(std::string* error) const;
};

struct SicpRowMisfit {
  std::size_t points = 0;     // face points in the plane fit; 0: not fitted
  // Scan points of the flank within radius_mm (the model's normal there within 30 deg of square to the row's tool
  // axis): they measure where the edge lies across, whatever the face's fit.
  std::size_t flank_points = 0;
  double offset_mm = 0.0;     // a: the scanned surface off the model's at the row, along its normal
  double offset_se_mm = 0.0;  // its standard error
  // The compensated tool normal against the predicted one tilted by (b, c), split into its tilt along the path (about
  // the across direction: from b) and across it (from c), each with its slope's significance |b| / se(b), |c| /
  // se(c). Along the path the slope is measured over the disc's full width, across it over the half on the face.
  double normal_error_deg = 0.0;
  double along_error_deg = 0.0;
  double along_z = 0.0;
  double across_error_deg = 0.0;
  double across_z = 0.0;
  double dent_mm = 0.0;             // k: the bump's depth at the row (> 0: the scan above the model's surface)
  double dent_z = 0.0;              // |k| / se(k); 0: not fitted
  double dent_slope_deg = 0.0;      // the slope the bump implies at its steepest
  std::size_t near_points = 0;      // face points within near_radius_mm (0: too few, under 5)
  double local_offset_mm = 0.0;     // their mean residual minus the neighbours' (the two sides averaged)
  double local_offset_se_mm = 0.0;  // its standard error (0: no neighbours)
};

// The residual of scan point q (scan frame) against the model's image of the nominal surface at trajectory row
// `row` (the model's transform there): its signed distance along the model's normal, and that normal (scan frame,
// unit). False when q has no pair on the nominal surface.
using SicpModelResidual =
    std::function<bool(const Eigen::Vector3d& q, std::size_t row, double& residual_mm, Eigen::Vector3d& normal)>;

// compensated: the path (points and its final, smoothed tool normals). predicted_normals: the tool normals the model
// gave before smoothing (one per row). scan, scan_tree: the points the registration used and their index.
// noise_mm: the scan's noise (estimate_surface_noise). Throws conform::Error for invalid options or sizes.
std::vector<SicpRowMisfit> sicp_surface_misfit(const Trajectory& compensated,
                                               const std::vector<Eigen::Vector3d>& predicted_normals,
                                               const std::vector<Eigen::Vector3d>& scan, const KdTree& scan_tree,
                                               double noise_mm, const SicpModelResidual& residual,
                                               const SicpMisfitOptions& options);

}  // namespace conform
