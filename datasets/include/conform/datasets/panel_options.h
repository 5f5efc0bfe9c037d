#pragma once
// What `generate plate` and `generate nosecone` make: a composite panel with an opening (a porthole in a
// double-curvature plate, a cockpit-like window with corners in a barrel section), deformed by a known smooth field,
// scanned around the opening, with the deburring trajectory along the opening's edge and its deformed ground truth.
//
// Shapes, in the panel's own frame (mm):
//   plate:    z = x^2 / (2 Rx) + y^2 / (2 Ry) (double curvature), the porthole an ellipse (or a circle, or a rounded
//             rectangle) centred at (porthole_x, porthole_y); clamps along x = +-clamp_span / 2.
//   nosecone: a barrel of radius R about the x axis, S(x, s) = (x, R sin(s / R), R cos(s / R)), s the arc length
//             from the top; the opening a trapezoid in (x, s): bottom edge (x = -h/2) wide w_bottom, top edge (x =
//             +h/2) wide w_top, corners rounded with corner_radius (0: sharp).
// The opening has a flank: the panel's edge, `thickness` deep along -n, which the scanner sees and the tool deburrs.
// The nominal surface is the band of the panel within band_mm of the opening, plus the flank.
//
// The deformation (deformed = G * (p + D(p)), G a rigid motion):
//   plate:    D = w(x, y) e_z, w = -sag * beam(x) + bend * (2 (y - y_c) / W)^2 + twist * (2x / L)(2 (y - y_c) / W),
//   where
//             beam is the normalised deflection of a uniformly loaded simply supported beam between the clamps
//             (16/5 (xi - 2 xi^3 + xi^4), xi = x / L + 1/2, 1 at mid-span) and W the porthole's height.
//   nosecone: D = ovality cos(2 theta) e_r - droop ((x + L/2) / L)^2 e_z (the cross-section squashed under gravity,
//             the front drooping), theta = s / R.

#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "conform/core/progress.h"

namespace conform {

enum class PanelShape { kPlate, kNoseCone };
// The plate's opening: an ellipse (the porthole) or a rectangle porthole_width x porthole_height with corners rounded
// to corner_radius_mm (a cut-out).
enum class PlateOpening { kEllipse, kRoundedRectangle };

struct PanelOptions {
  PanelShape shape = PanelShape::kPlate;

  // --- plate ---
  double plate_radius_x_mm = 2500.0;  // Rx, curvature radius along x
  double plate_radius_y_mm = 4000.0;  // Ry
  double porthole_width_mm = 380.0;   // along x
  double porthole_height_mm = 260.0;  // along y; equal to the width (or round = true) for a round porthole
  bool round = false;                 // a circle of diameter porthole_width
  PlateOpening opening = PlateOpening::kEllipse;
  double porthole_x_mm = 60.0;  // centre, off the clamps' middle so the sag is not symmetric about it
  double porthole_y_mm = 30.0;
  double clamp_span_mm = 1000.0;  // L: clamps at x = +-L/2

  // --- nose cone ---
  double barrel_radius_mm = 1000.0;
  double window_height_mm = 440.0;   // h, along x
  double window_bottom_mm = 900.0;   // w_bottom, arc length at x = -h/2
  double window_top_mm = 600.0;      // w_top, arc length at x = +h/2
  double corner_radius_mm = 3.0;     // 0: sharp corners (also the plate's rounded rectangle)
  double barrel_length_mm = 1400.0;  // L of the droop

  // --- both ---
  double band_mm = 40.0;               // nominal surface and scan: the panel within this of the opening
  double thickness_mm = 4.0;           // depth of the flank
  double surface_edge_mm = 2.0;        // edge length of the nominal surface mesh
  double contour_spacing_mm = 0.24;    // between contour points (~10,000 for the default nose cone)
  double trajectory_spacing_mm = 1.0;  // between trajectory points
  std::int64_t scan_points = 0;        // 0: default_scan_points(shape)
  double noise_mm = 0.05;              // Gaussian, along the deformed surface normal, sigma
  double missing_fraction = 0.0;       // share of the contour's length, in `missing_patches` arcs, with no scan near it
  int missing_patches = 4;
  double missing_depth_mm = 15.0;  // how far from the edge a missing arc reaches
  int holes = 0;                   // more missing discs of the scan, at seeded places on the band
  double hole_radius_mm = 10.0;
  // false: the scanner sees the band on the material side only, not the opening's flank (a one-sided scan: a laser
  // line looking straight down, a handheld scan of the face); the nominal surface keeps its flank.
  bool scan_flank = true;
  // Stray points: this share of the scan drawn again anywhere over the band's bounding box, 1-20 mm off the surface
  // along its normal (spikes, reflections, dust), in [0, 0.2].
  double stray_fraction = 0.0;
  // A laser-stripe scan: each point moved within its face to the nearest of the planes d . p = k stripe_spacing_mm,
  // d = (cos a, sin a, 0) for a = stripe_angle_deg (the nominal frame; at 0 the planes x = k spacing: the plate's
  // stripes run across its x axis, the nose cone's round its barrel), so that the scan lies on lines this far apart,
  // as densely along each as the points allow; a point the move would take out of its face, and faces nearly parallel
  // to the planes (the flank where it runs across d), are left out. 0: points spread evenly over the surface; else in [0.2, 20]. The angle in [-90, 90] deg.
  double stripe_spacing_mm = 0.0;
  double stripe_angle_deg = 0.0;

  // --- the deformation ---
  double sag_mm = 4.0;      // plate: mid-span sag between the clamps
  double bend_mm = 1.5;     // plate: bending across
  double twist_mm = 1.5;    // plate: twist
  double ovality_mm = 3.0;  // nose cone
  double droop_mm = 4.0;    // nose cone
  // Both: a seeded smooth non-rigid field (three sine waves per axis, wavelengths 1-2 x field_wavelength, random
  // directions and phases): |D_z| <= field_mm, |D_x|, |D_y| <= field_mm / 2 (in the plane: it moves the edge across).
  double field_mm = 0.0;
  double field_wavelength_mm = 400.0;
  // A local dent at the opening's edge, dent_depth_mm into the part (plate: along -z; nose cone: towards the barrel's
  // axis) with a Gaussian profile of full width dent_width_mm (where it falls to 1/e^2 of its depth: 4 sigma) in the
  // parameter plane ((x, y); nose cone: (x, arc length)), centred where the ray from the opening's centre at the angle
  // dent_at x 360 deg (from +x, counter-clockwise) meets the edge; dent_at in [0, 1). 0: none.
  double dent_depth_mm = 0.0;
  double dent_width_mm = 20.0;
  double dent_at = 0.3;
  Eigen::Vector3d rotation_deg = Eigen::Vector3d(0.3, -0.2, 0.4);    // G: rotation vector, degrees
  Eigen::Vector3d translation_mm = Eigen::Vector3d(1.5, -1.0, 2.0);  // G: translation

  std::uint64_t seed = 1;
  ProgressFn progress;  // stages "panel: surface", "panel: scan"

  // False (and why, naming the option) for a value out of range or not finite, or a size that would exhaust memory.
  bool IsValid(std::string* error) const;
};

const char* to_string(PanelShape shape);
const char* to_string(PlateOpening opening);

// The scan points drawn (before the missing parts are cut) when PanelOptions::scan_points is 0.
std::int64_t default_scan_points(PanelShape shape);

// The held-out harder plates of the S-ICP docs and tests: the default plate plus a smooth field of 6 mm (up to ~7 mm
// of non-rigid displacement over the part with the sag), 0.05 mm noise, and the given opening (rounded rectangle
// with 6 mm corners).
PanelOptions harder_plate(PlateOpening opening, std::uint64_t seed);

}  // namespace conform
