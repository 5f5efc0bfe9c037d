#include "conform/datasets/panel_options.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace conform {
namespace {

bool fail(std::string* error, const std::string& message) {
  if (error != nullptr) *error = message;
  return false;
}

std::string number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

bool check_shape(const PanelOptions& o, std::string* error) {
  if (o.shape == PanelShape::kPlate) {
    if (!positive(o.plate_radius_x_mm) || !positive(o.plate_radius_y_mm))
      return fail(error, "plate curvature radii must be > 0 mm");
    if (!positive(o.porthole_width_mm) || (!o.round && !positive(o.porthole_height_mm)))
      return fail(error, "porthole width and height must be > 0 mm");
    if (!std::isfinite(o.porthole_x_mm) || !std::isfinite(o.porthole_y_mm))
      return fail(error, "porthole centre must be finite");
    if (!positive(o.clamp_span_mm)) return fail(error, "clamp span must be > 0 mm");
    if (o.opening == PlateOpening::kRoundedRectangle &&
        (!std::isfinite(o.corner_radius_mm) || o.corner_radius_mm < 0.0 ||
         2.0 * o.corner_radius_mm >=
             std::min(o.porthole_width_mm, o.round ? o.porthole_width_mm : o.porthole_height_mm)))
      return fail(error, "corner radius must be >= 0 mm and less than half the cut-out's smaller side, got " +
                             number(o.corner_radius_mm));
    return true;
  }
  if (!positive(o.barrel_radius_mm)) return fail(error, "barrel radius must be > 0 mm");
  if (!positive(o.window_height_mm) || !positive(o.window_bottom_mm) || !positive(o.window_top_mm))
    return fail(error, "window height and widths must be > 0 mm");
  if (std::max(o.window_bottom_mm, o.window_top_mm) + 2.0 * o.band_mm >= 2.0 * M_PI * o.barrel_radius_mm)
    return fail(error, "window (plus band) wider than the barrel's circumference");
  if (!std::isfinite(o.corner_radius_mm) || o.corner_radius_mm < 0.0 ||
      2.0 * o.corner_radius_mm >= std::min({o.window_height_mm, o.window_bottom_mm, o.window_top_mm}))
    return fail(error, "corner radius must be >= 0 mm and less than half the window's smallest side, got " +
                           number(o.corner_radius_mm));
  if (!positive(o.barrel_length_mm)) return fail(error, "barrel length must be > 0 mm");
  return true;
}

bool check_sampling(const PanelOptions& o, std::string* error) {
  if (!positive(o.band_mm)) return fail(error, "band must be > 0 mm, got " + number(o.band_mm));
  if (!positive(o.thickness_mm)) return fail(error, "thickness must be > 0 mm, got " + number(o.thickness_mm));
  if (!positive(o.surface_edge_mm) || o.surface_edge_mm < 0.05)
    return fail(error, "surface edge must be >= 0.05 mm, got " + number(o.surface_edge_mm));
  if (!positive(o.contour_spacing_mm) || o.contour_spacing_mm < 0.01)
    return fail(error, "contour spacing must be >= 0.01 mm, got " + number(o.contour_spacing_mm));
  if (!positive(o.trajectory_spacing_mm) || o.trajectory_spacing_mm < 0.01)
    return fail(error, "trajectory spacing must be >= 0.01 mm, got " + number(o.trajectory_spacing_mm));
  if (o.scan_points < 0 || o.scan_points > 50000000)
    return fail(error, "scan points must be in [0, 5e7] (0: the default), got " + std::to_string(o.scan_points));
  if (!std::isfinite(o.noise_mm) || o.noise_mm < 0.0) return fail(error, "noise must be >= 0 mm");
  if (!std::isfinite(o.missing_fraction) || o.missing_fraction < 0.0 || o.missing_fraction > 0.9)
    return fail(error, "missing fraction must be in [0, 0.9], got " + number(o.missing_fraction));
  if (o.missing_patches < 1 || o.missing_patches > 1000) return fail(error, "missing patches must be in [1, 1000]");
  if (!std::isfinite(o.missing_depth_mm) || o.missing_depth_mm < 0.0) return fail(error, "missing depth must be >= 0");
  if (o.holes < 0 || o.holes > 10000) return fail(error, "holes must be in [0, 10000]");
  if (!std::isfinite(o.hole_radius_mm) || o.hole_radius_mm < 0.0) return fail(error, "hole radius must be >= 0 mm");
  if (!std::isfinite(o.stray_fraction) || o.stray_fraction < 0.0 || o.stray_fraction > 0.2)
    return fail(error, "stray fraction must be in [0, 0.2], got " + number(o.stray_fraction));
  if (!std::isfinite(o.stripe_spacing_mm) || (o.stripe_spacing_mm != 0.0 && (o.stripe_spacing_mm < 0.2 ||
                                                                             o.stripe_spacing_mm > 20.0)))
    return fail(error, "stripe spacing must be 0 or in [0.2, 20] mm, got " + number(o.stripe_spacing_mm));
  if (!std::isfinite(o.stripe_angle_deg) || o.stripe_angle_deg < -90.0 || o.stripe_angle_deg > 90.0)
    return fail(error, "stripe angle must be in [-90, 90] deg, got " + number(o.stripe_angle_deg));
  if (!std::isfinite(o.dent_depth_mm) || std::abs(o.dent_depth_mm) > 100.0)
    return fail(error, "dent depth must be in [-100, 100] mm, got " + number(o.dent_depth_mm));
  if (!positive(o.dent_width_mm) || o.dent_width_mm > 1000.0)
    return fail(error, "dent width must be in (0, 1000] mm, got " + number(o.dent_width_mm));
  if (!std::isfinite(o.dent_at) || o.dent_at < 0.0 || o.dent_at >= 1.0)
    return fail(error, "dent place must be in [0, 1), got " + number(o.dent_at));
  return true;
}

}  // namespace

const char* to_string(PanelShape shape) { return shape == PanelShape::kPlate ? "plate" : "nosecone"; }

const char* to_string(PlateOpening opening) {
  return opening == PlateOpening::kEllipse ? "ellipse" : "rounded_rectangle";
}

std::int64_t default_scan_points(PanelShape shape) { return shape == PanelShape::kPlate ? 120000 : 300000; }

PanelOptions harder_plate(PlateOpening opening, std::uint64_t seed) {
  PanelOptions o;
  o.shape = PanelShape::kPlate;
  o.opening = opening;
  o.corner_radius_mm = 6.0;
  o.field_mm = 6.0;
  o.noise_mm = 0.05;
  o.seed = seed;
  return o;
}

bool PanelOptions::IsValid(std::string* error) const {
  if (!check_shape(*this, error) || !check_sampling(*this, error)) return false;
  const double deformation[] = {sag_mm, bend_mm, twist_mm, ovality_mm, droop_mm, field_mm};
  if (!std::isfinite(field_wavelength_mm) || field_wavelength_mm < 10.0 || field_wavelength_mm > 1e6)
    return fail(error, "field wavelength must be in [10, 1e6] mm, got " + number(field_wavelength_mm));
  for (double d : deformation) {
    if (!std::isfinite(d) || std::abs(d) > 1000.0) return fail(error, "deformation amplitudes must be finite, < 1 m");
  }
  if (!rotation_deg.allFinite() || rotation_deg.norm() > 90.0) return fail(error, "rotation must be below 90 deg");
  if (!translation_mm.allFinite()) return fail(error, "translation must be finite");
  // A rough perimeter bound keeps absurd sizes from exhausting memory.
  const double perimeter = shape == PanelShape::kPlate
                               ? M_PI * std::max(porthole_width_mm, porthole_height_mm)
                               : 2.0 * (window_height_mm + std::max(window_bottom_mm, window_top_mm)) + 1.0;
  const double cells = (perimeter + M_PI * band_mm) / surface_edge_mm * ((band_mm + thickness_mm) / surface_edge_mm);
  if (cells > 2e7) return fail(error, "surface edge " + number(surface_edge_mm) + " mm makes too many triangles");
  if (perimeter / contour_spacing_mm > 2e7 || perimeter / trajectory_spacing_mm > 2e7)
    return fail(error, "contour or trajectory spacing too small: more than 2e7 points");
  return true;
}

}  // namespace conform
