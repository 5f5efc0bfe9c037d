// conform.inspect (issue 33): the CLI's `conform inspect` as a library call, the same pipeline and the same JSON.

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/core/units.h"
#include "conform/pipelines/inspect/inspect.h"
#include "conform/pipelines/inspect/inspect_json.h"
#include "conform/pipelines/inspect/inspect_report.h"
#include "job_report.h"

namespace conform::python {

namespace {

using py::arg;

py::tuple job_inspect(const py::object& scan, const py::object& reference, const py::object& transform,
                      const std::optional<std::string>& align, const std::vector<std::size_t>& datums,
                      double max_distance, double max_normal_angle_deg, double form_trim, std::size_t min_fit_points,
                      const py::object& tolerances, const py::object& out_faces, const std::string& units,
                      const py::object& cad_deflection, const py::object& cad_angle_deg,
                      const py::object& cad_save_mesh, const py::object& report, const py::object& progress_callback) {
  const std::string report_path = report_path_of(report);
  Inputs inputs;
  InspectOptions options;
  set_cad_options(cad_deflection, cad_angle_deg, cad_save_mesh, options.cad);
  options.scan_path = inputs.geometry(scan, "scan");
  options.reference_path = path_of(reference);
  options.transform_path = inputs.transform(transform, "transform");
  if (align && *align != "best-fit") throw Error("align must be 'best-fit' or None, not '" + *align + "'");
  options.best_fit = align.has_value();
  options.datum_faces = datums;
  options.max_distance_mm = max_distance;
  options.max_normal_angle_rad = radians(max_normal_angle_deg);
  options.form_trim = form_trim;
  options.min_fit_points = min_fit_points;
  options.tolerances_path = path_of(tolerances);
  options.out_faces_path = path_of(out_faces);
  options.mm_per_unit = millimetres_per_unit(units);
  const Progress progress(progress_callback);
  options.progress = progress.function();
  options.cad.progress = options.progress;
  options.keep_geometry = !report_path.empty();
  CallFiles files({options.scan_path, options.reference_path, options.transform_path, options.tolerances_path},
                  {options.out_faces_path, options.cad.save_mesh_path, report_path});
  InspectResult result = released(progress, [&] { return run_inspect(options); });
  const nlohmann::json j = inspect_json(options, result, units);
  if (!report_path.empty()) write_report(report_path, inspect_report(options, result, j, ""));
  files.commit();
  py::dict arrays;
  arrays["warnings"] = py::cast(result.warnings);
  std::vector<std::int64_t> face(result.point_face.begin(), result.point_face.end());
  arrays["point_face"] = owned(std::move(face));
  std::vector<std::string> in_memory;
  if (inputs.in_memory(options.scan_path)) in_memory.push_back("scan");
  if (inputs.in_memory(options.transform_path)) in_memory.push_back("transform");
  return answer(j, arrays, in_memory);
}

}  // namespace

void bind_inspect_job(py::module_& m) {
  const InspectOptions defaults;
  m.def("inspect", &job_inspect, arg("scan"), arg("reference"), py::kw_only(), arg("transform") = py::none(),
        arg("align") = py::none(), arg("datums") = std::vector<std::size_t>(),
        arg("max_distance") = defaults.max_distance_mm, arg("max_normal_angle_deg") = 30.0,
        arg("form_trim") = defaults.form_trim, arg("min_fit_points") = defaults.min_fit_points,
        arg("tolerances") = py::none(), arg("out_faces") = py::none(), arg("units") = "mm",
        arg("cad_deflection") = py::none(), arg("cad_angle_deg") = py::none(), arg("cad_save_mesh") = py::none(),
        arg("report") = py::none(), arg("progress") = py::none());
}

}  // namespace conform::python
