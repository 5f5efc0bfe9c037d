#pragma once
// Profile compensation (Chen et al., "A 3D-compensating algorithm for LNG shipbuilding profiles robot cutting
// system"): where each designed feature of a straight, flat profile must be cut on the deformed profile that the laser
// sensor measured, so that it lands at its design position once the profile is straightened and flattened.
//
//   edge points -> checks (order within the noise, gaps, duplicates) -> robust edge model (cubic, spline or auto by
//   BIC, outliers rejected; profile_edge.h) -> feature checks (Ty on the edge, Tx on the web, units)
//   -> web direction (global Z: machine +z as in the paper, or given, or the plane of the points on request; local:
//   from a second edge; profile_map.h) -> each feature sampled at the chord tolerance and mapped,
//   P' = C(t) + Tx V1(t) with s(t) = Ty (Eq. 4-7), with the tool's frame (web normal, cut direction) at every point
//   -> per feature, the worst distance to where the cubic model alone would put the same points.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/compensation/profile_edge.h"
#include "conform/compensation/profile_features.h"
#include "conform/compensation/profile_map.h"

namespace conform {

struct ProfileCompensationOptions {
  ProfileEdgeFitOptions edge;                 // model, checks, noise (also used for the second edge)
  ProfileSampleOptions sampling;              // chord tolerance of mapped outlines
  std::optional<Eigen::Vector3d> web_normal;  // global Z; empty: machine +z (the paper), unless fit_web_plane
  bool fit_web_plane = false;                 // Z = the normal of the edge points' plane (only on request)
  double web_plane_warning_deg = 0.5;         // a fitted plane tilted more than this from +z is warned about
                                              // (it moves a feature by Tx sin(tilt): 0.9 mm at Tx = 100 mm)
  double web_width_mm = 0.0;                  // the web's width: features beyond Tx = width are refused; 0: unknown
  bool reversed = false;                      // the edge points are listed from the profile's far end
  double arc_length_tolerance_mm = 1e-7;      // |s(t) - Ty| at every mapped point, mm (> 0)
  // A feature over a stretch of edge without readings longer than this is warned about (its position there is
  // interpolated: a kink or bend within the stretch is not seen); 0: 4 x the median spacing, at least 20 mm.
  double gap_warning_mm = 0.0;

  bool IsValid(std::string* error) const;
};

struct ProfileFeatureResult {
  std::string id;
  ProfileFeatureType type = ProfileFeatureType::kPoint;
  bool has_centre = false;  // circle, slot
  Eigen::Vector2d designed_centre = Eigen::Vector2d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // mapped centre
  std::vector<Eigen::Vector2d> designed;             // sampled outline (closed ones end on their first point)
  std::vector<Eigen::Vector3d> mapped;               // where to cut or mark, mm
  std::vector<Eigen::Vector3d> normals;              // the web's normal at each mapped point (the tool axis), unit
  std::vector<Eigen::Vector3d> directions;           // the cut direction there: along the mapped outline, unit
  Eigen::Vector3d centre_normal = Eigen::Vector3d::UnitZ();     // at the centre
  Eigen::Vector3d centre_direction = Eigen::Vector3d::UnitX();  // the edge's direction at the centre's Ty
  double cubic_deviation_max_mm = 0.0;  // worst |P' - P'_cubic| over the outline and centre; 0 when the model is cubic
  // What the measurement cannot tell about this feature: it lies over a stretch of edge without readings, or twist is
  // not observed (one edge) and moves it by Tx sin(twist).
  std::vector<std::string> warnings;
  double gap_mm = 0.0;            // the longest stretch without readings under it (0: none beyond the limit)
  double twist_mm_per_deg = 0.0;  // one edge: how far 1 deg of twist moves it (max Tx x sin 1 deg); else 0
};

struct ProfileCompensationResult {
  bool ok = false;
  std::string termination = "not run";
  ProfileEdgeFit edge;
  std::optional<ProfileEdgeFit> second_edge;
  bool local_web = false;                                 // V1 from the second edge
  std::string web_source = "machine +z";                  // "machine +z", "given", "fitted plane", "second edge"
  Eigen::Vector3d web_normal = Eigen::Vector3d::UnitZ();  // global Z; unused when local
  double web_flatness_ratio = 0.0;                        // of the fitted plane; 0 otherwise
  double web_tilt_deg = 0.0;                              // angle between the global Z used and machine +z
  std::vector<std::string> warnings;                      // the edge fit's and the web's
  double web_width_min_mm = 0.0;                          // local: measured web width over the mapped points
  double web_width_max_mm = 0.0;
  std::vector<ProfileFeatureResult> features;
  std::size_t mapped_points = 0;
  double arc_length_residual_max_mm = 0.0;  // max |s(t) - Ty| over every mapped point (Eq. 7)
  double cubic_deviation_max_mm = 0.0;      // max over the features
};

// Throws conform::Error naming the source and the problem: invalid options, edge points that fail the checks
// (profile_edge_points.h, profile_edge.h), a feature that fails ProfileFeature::validate, reaches Ty outside the
// measured edge [0, length] or Tx outside the web [0, width] (width given or measured by the second edge), features
// that look like metres against an edge in mm, a second edge on the wrong side of the edge (measured from the far
// end: reversed), an undetermined web normal. ok is false (with a termination) when an arc-length inversion did not
// meet its tolerance.
ProfileCompensationResult compensate_profile(const std::vector<Eigen::Vector3d>& edge_points,
                                             const std::vector<ProfileFeature>& features,
                                             const ProfileCompensationOptions& options,
                                             const std::vector<Eigen::Vector3d>* second_edge_points = nullptr,
                                             const std::string& edge_source = "edge points",
                                             const std::string& second_edge_source = "second edge points");

}  // namespace conform
