#pragma once
// A robot's tool trajectory (positions and unit tool normals, in order) and its update onto the deformed part:
// each nominal trajectory point takes the transform(s) of its place on the nominal contour (Subdivision-ICP's blended
// segment transforms, or one rigid transform), and its tool normal is estimated again from the scan around the new
// position, or rotated with the transform where the scan has too little data there.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/core/polyline.h"
#include "conform/registration/contour_segments.h"

namespace conform {

class KdTree;

struct Trajectory {
  std::vector<Eigen::Vector3d> points;   // mm
  std::vector<Eigen::Vector3d> normals;  // unit, one per point
};

struct ToolNormalOptions {
  // false: every normal is the nominal one rotated with the blended transforms, which measures best on the generated
  // parts (mean error 0.03-0.19 deg against 0.9-1.1 deg fitted to the scan, docs/sicp.md); true: fitted to the scan.
  bool from_scan = false;
  double radius_mm = 5.0;       // scan points this close to the new position fit the plane
  double slab_mm = 0.5;         // ... and this close to the predicted plane (the edge's flank drops out)
  std::size_t min_points = 12;  // fewer: the rotated normal is kept
  double max_tilt_rad = 0.35;   // a fitted normal more than this from the predicted one is not trusted (20 deg)
  // The normals are then averaged along the path over rows within this arc length (triangular weights), so that
  // consecutive rows turn no more than the part does (plane fits to a noisy scan jitter by tenths of a degree). 0: not
  // smoothed. >= 0 mm.
  double smooth_mm = 30.0;
  bool IsValid(std::string* error) const;
};

// Arc length along the contour of each point's orthogonal projection onto the contour's nearest edges (continuous as
// the point moves, unlike its nearest contour vertex); with distances_mm, also each point's distance from that
// projection (from the contour's edges, not its vertices: a CAD contour may have 20 mm steps). Throws
// conform::Error for an empty contour.
std::vector<double> locate_on_contour(const Polyline& contour, const std::vector<double>& arc_length_mm,
                                      const std::vector<Eigen::Vector3d>& points,
                                      std::vector<double>* distances_mm = nullptr);

// Positions and predicted normals by the blended segment transforms (T_scan_nominal, one per segment).
Trajectory map_by_segments(const Trajectory& nominal, const Polyline& contour, const ContourSegmentation& segmentation,
                           const std::vector<Eigen::Isometry3d>& T_scan_nominal);
// Positions and normals by one rigid transform.
Trajectory map_rigidly(const Trajectory& nominal, const Eigen::Isometry3d& T_scan_nominal);

// Replaces each normal by the plane fitted to the scan points around its point (options above); returns how many
// came from the scan (the rest keep the predicted normal). scan_tree indexes scan.
std::size_t reestimate_tool_normals(Trajectory& trajectory, const std::vector<Eigen::Vector3d>& scan,
                                    const KdTree& scan_tree, const ToolNormalOptions& options);

// Averages each unit normal with its neighbours' within window_mm of arc length along the path (weight 1 - d /
// window_mm), renormalised; a closed path (its ends within three median row spacings) wraps. window_mm <= 0: unchanged.
void smooth_tool_normals(Trajectory& trajectory, double window_mm);

// Throws conform::Error (naming `what`) when normals are not one per point, a value is not finite or a normal is
// not of unit length (within 1e-3).
void check_trajectory(const Trajectory& trajectory, const std::string& what);

}  // namespace conform
