#pragma once
// The HTML report of `conform fit-cylinder --report` (docs/report.md): the verdict (a cylinder or why not), the
// points coloured by their signed residual (green within the inlier threshold), the fitted cylinder as a
// semi-transparent mesh over the points' extent along the axis, the axis as a line, the figures and the residual
// histogram.

#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/fit_cylinder/fit_cylinder.h"
#include "conform/report/page.h"

namespace conform {

// `result` from run_fit_cylinder with options.keep_geometry; `json` is fit_cylinder_json of it.
html::Page fit_cylinder_report(const FitCylinderJobOptions& options, const FitCylinderJobResult& result,
                               const nlohmann::json& json, const std::string& date);

// The cylinder's surface between axis parameters t0 < t1 (mm along the axis from its point): `segments` around,
// `rings` + 1 circles along; outward normals, faces counter-clockwise seen from outside.
Mesh cylinder_mesh(const Cylinder& cylinder, double t0, double t1, int segments = 96, int rings = 8);

}  // namespace conform
