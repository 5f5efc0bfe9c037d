#include "inspect/inspect_faces_csv.h"

#include <cmath>

namespace conform::detail {

namespace {

void number_or_empty(CsvWriter& csv, bool has, double value) {
  if (has && std::isfinite(value)) {
    csv.cell(value);
  } else {
    csv.cell(std::string_view());
  }
}

}  // namespace

CsvWriter faces_csv(const InspectResult& result) {
  CsvWriter csv({"id", "type", "points", "deviation_to", "centroid_x_mm", "centroid_y_mm", "centroid_z_mm", "mean_mm",
                 "std_mm", "min_mm", "max_mm", "form_mm", "form_reference", "radius_mm", "nominal_radius_mm",
                 "axis_offset_mm", "axis_angle_deg", "position_mm", "perpendicularity_mm", "angle_to_nominal_deg", "plane_offset_mm", "verdict"});
  for (const FaceInspection& f : result.faces) {
    const bool seen = f.points > 0;
    const bool cylinder = f.fitted && f.nominal.type == CadSurfaceType::kCylinder;
    const bool sphere = f.fitted && f.nominal.type == CadSurfaceType::kSphere;
    const bool plane = f.fitted && f.nominal.type == CadSurfaceType::kPlane;
    const bool cone = f.fitted && f.nominal.type == CadSurfaceType::kCone;
    const bool torus = f.fitted && f.nominal.type == CadSurfaceType::kTorus;
    csv.cell(static_cast<std::int64_t>(f.id)).cell(to_string(f.nominal.type));
    csv.cell(static_cast<std::int64_t>(f.points)).cell(f.exact ? "exact surface" : "mesh");
    for (int k = 0; k < 3; ++k) number_or_empty(csv, seen, f.centroid_mm[k]);
    number_or_empty(csv, seen, f.deviation.mean_mm);
    number_or_empty(csv, seen, f.deviation.std_mm);
    number_or_empty(csv, seen, f.deviation.min_mm);
    number_or_empty(csv, seen, f.deviation.max_mm);
    number_or_empty(csv, f.form_measured, f.form.width_mm);
    csv.cell(f.form_measured ? f.form_reference : "");
    number_or_empty(csv, cylinder || sphere || cone || torus, f.radius_mm);
    const CadSurfaceType t = f.nominal.type;
    const bool has_nominal_radius =
        cone || t == CadSurfaceType::kCylinder || t == CadSurfaceType::kSphere || t == CadSurfaceType::kTorus;
    number_or_empty(csv, has_nominal_radius, f.nominal_radius_mm);
    number_or_empty(csv, cylinder || cone, f.axis_offset_mm);
    number_or_empty(csv, cylinder || cone || torus, f.axis_angle_deg);
    number_or_empty(csv, cylinder, f.position_mm);
    number_or_empty(csv, cylinder, f.perpendicularity_mm);
    number_or_empty(csv, plane, f.angle_to_nominal_deg);
    number_or_empty(csv, plane, f.plane_offset_mm);
    csv.cell(!f.verdict ? "" : !f.verdict->measured ? "not measured" : f.verdict->pass ? "pass" : "fail");
    csv.end_row();
  }
  return csv;
}

}  // namespace conform::detail
