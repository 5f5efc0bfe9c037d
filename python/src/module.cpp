// conform._conform: the jobs of the `conform` CLI for Python (python/conform/__init__.py wraps them). Each call maps
// its keyword arguments (the CLI's option names, defaults read from the pipelines' Options) onto the same pipeline
// the CLI runs, with the GIL released, and returns (the CLI's JSON as text, per-point arrays). Arrays are views over
// the result's own vectors (moved, not copied), and over the Geometry conform.read returns. The measuring jobs
// are here, the path-planning ones and the generators in toolpath_jobs.cpp.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "conform/core/error.h"
#include "conform/core/io.h"
#include "conform/core/units.h"
#include "conform/pipelines/align/align_json.h"
#include "conform/pipelines/align/align_report.h"
#include "conform/pipelines/compare/compare_json.h"
#include "conform/pipelines/compare/compare_report.h"
#include "conform/pipelines/common/deviation_colours.h"
#include "conform/pipelines/common/deviation_histogram.h"
#include "conform/pipelines/export/export_json.h"
#include "conform/pipelines/fit_cylinder/fit_cylinder_json.h"
#include "conform/pipelines/fit_cylinder/fit_cylinder_report.h"
#include "conform/pipelines/generate/generate_eroded_json.h"
#include "conform/pipelines/generate/generate_profile_json.h"
#include "conform/pipelines/pose_error/pose_error_json.h"
#include "conform/pipelines/saddle/saddle_json.h"
#include "conform/pipelines/saddle/saddle_report.h"
#include "inputs.h"
#include "job_report.h"

namespace conform::python {
namespace {

std::shared_ptr<Geometry> job_read(const py::object& path_value, const std::string& units,
                                   const py::object& cad_deflection, const py::object& cad_angle_deg) {
  auto geometry = std::make_shared<Geometry>();
  geometry->path = path_of(path_value);
  const double mm_per_unit = millimetres_per_unit(units);
  ReadOptions read;
  set_cad_options(cad_deflection, cad_angle_deg, py::none(), read.cad);
  py::gil_scoped_release release;
  ReadReport report;
  geometry->mesh = read_geometry(geometry->path, read, &report);
  if (mm_per_unit != 1.0) scale_in_place(geometry->mesh, mm_per_unit);
  geometry->warnings = report.warnings;
  return geometry;
}

// One input's units: its own when given, else the job's `units` (the CLI's --scan-units / --reference-units over
// --units).
const std::string& units_of(const std::optional<std::string>& own, const std::string& units) {
  return own ? *own : units;
}

py::array rows_view(const py::object& self, std::vector<Eigen::Vector3d>& rows) {
  const py::ssize_t n = static_cast<py::ssize_t>(rows.size());
  return py::array_t<double>({n, py::ssize_t{3}}, {py::ssize_t{sizeof(Eigen::Vector3d)}, py::ssize_t{sizeof(double)}},
                             rows.empty() ? nullptr : rows.front().data(), self);
}

py::array faces_view(const py::object& self, std::vector<Face>& faces) {
  const py::ssize_t n = static_cast<py::ssize_t>(faces.size());
  return py::array_t<std::int32_t>({n, py::ssize_t{3}}, {py::ssize_t{sizeof(Face)}, py::ssize_t{sizeof(std::int32_t)}},
                                   faces.empty() ? nullptr : faces.front().data(), self);
}

py::tuple job_compare(const py::object& scan, const py::object& reference, const py::object& transform,
                      std::optional<double> tolerance, const py::object& out_deviation, const py::object& out_histogram,
                      const std::string& units, const std::optional<std::string>& scan_units,
                      const std::optional<std::string>& reference_units, bool flat_facets, const py::object& cad_deflection,
                      const py::object& cad_angle_deg, const py::object& cad_save_mesh, const py::object& report,
                      const py::object& progress_callback) {
  const std::string report_path = report_path_of(report);
  Inputs inputs;
  CompareOptions options;
  options.flat_facets = flat_facets;
  set_cad_options(cad_deflection, cad_angle_deg, cad_save_mesh, options.cad);
  options.scan_path = inputs.geometry(scan, "scan");
  options.reference_path = inputs.geometry(reference, "reference");
  options.transform_path = inputs.transform(transform, "transform");
  options.scan_mm_per_unit = millimetres_per_unit(units_of(scan_units, units));
  options.reference_mm_per_unit = millimetres_per_unit(units_of(reference_units, units));
  options.tolerance_mm = tolerance;
  options.out_deviation_path = path_of(out_deviation);
  options.out_histogram_path = path_of(out_histogram);
  options.colour = deviation_colour;
  const std::string title = "Deviation of " + std::filesystem::path(options.scan_path).filename().string() + " from " +
                            std::filesystem::path(options.reference_path).filename().string();
  options.histogram = [title](const std::vector<double>& d, const DeviationStatistics& s) {
    return deviation_histogram_png(d, s, title);
  };
  const Progress progress(progress_callback);
  options.progress = progress.function();
  options.keep_geometry = !report_path.empty();
  CallFiles files({options.scan_path, options.reference_path, options.transform_path},
                  {options.out_deviation_path, options.out_histogram_path, report_path, options.cad.save_mesh_path});
  CompareResult result = released(progress, [&] { return run_compare(options); });
  const nlohmann::json j = compare_json(options, result, units_of(scan_units, units), units_of(reference_units, units));
  if (!report_path.empty()) write_report(report_path, compare_report(options, result, j, ""));
  files.commit();
  py::dict arrays;
  arrays["warnings"] = py::cast(result.warnings);
  arrays["deviation_mm"] = owned(std::move(result.deviation.deviation_mm));
  arrays["closest_mm"] = owned(std::move(result.deviation.closest));
  std::vector<std::string> in_memory;
  if (inputs.in_memory(options.scan_path)) in_memory.push_back("scan");
  if (inputs.in_memory(options.reference_path)) in_memory.push_back("reference");
  if (inputs.in_memory(options.transform_path)) in_memory.push_back("transform");
  return answer(j, arrays, in_memory);
}

py::tuple job_align(const py::object& scan, const py::object& reference, const std::string& method,
                    const std::string& init, double max_distance, double overlap, int max_iterations,
                    double free_tolerance_mm, double free_tolerance_deg, double pose_tolerance_mm, double tolerance,
                    double max_noise_ratio, const std::string& units, const std::optional<std::string>& scan_units,
                    const std::optional<std::string>& reference_units, const py::object& out_transform,
                    const py::object& out_aligned, const py::object& cad_deflection, const py::object& cad_angle_deg,
                    const py::object& cad_save_mesh, const py::object& report, const py::object& progress_callback) {
  const std::string report_path = report_path_of(report);
  Inputs inputs;
  AlignOptions options;
  set_cad_options(cad_deflection, cad_angle_deg, cad_save_mesh, options.cad);
  options.scan_path = inputs.geometry(scan, "scan");
  options.reference_path = inputs.geometry(reference, "reference");
  options.scan_mm_per_unit = millimetres_per_unit(units_of(scan_units, units));
  options.reference_mm_per_unit = millimetres_per_unit(units_of(reference_units, units));
  set_align_method(method, &options);
  set_align_init(init, &options);
  options.max_distance_mm = max_distance;
  options.overlap = overlap;
  options.max_iterations = max_iterations;
  options.free_tolerance_mm = free_tolerance_mm;
  options.free_tolerance_deg = free_tolerance_deg;
  options.pose_tolerance_mm = pose_tolerance_mm;
  options.tolerance_mm = tolerance;
  options.max_noise_ratio = max_noise_ratio;
  options.out_transform_path = path_of(out_transform);
  options.out_aligned_path = path_of(out_aligned);
  const Progress progress(progress_callback);
  options.progress = progress.function();
  options.keep_geometry = !report_path.empty();
  CallFiles files({options.scan_path, options.reference_path, init.rfind("pairs:", 0) == 0 ? init.substr(6) : ""},
                  {options.out_transform_path, options.out_aligned_path, report_path, options.cad.save_mesh_path});
  const AlignResult result = released(progress, [&] { return run_align(options); });
  const nlohmann::json j = align_json(result);
  if (!report_path.empty()) write_report(report_path, align_report(options, result, j, ""));
  files.commit();
  py::dict arrays;
  arrays["warnings"] = py::cast(result.warnings);
  return answer(j, arrays);
}

py::tuple job_export(const py::object& path, const std::string& format, const py::object& out, const py::object& frame,
                     double speed_mm_s, double approach_speed_mm_s, double approach_mm, const std::string& name,
                     const std::string& tool, const std::string& work_object, std::size_t max_points, bool three_axis,
                     double roll_cone_deg, const std::vector<double>& preferred_x, double blend_mm,
                     const std::string& process_on, const std::string& process_off,
                     const std::optional<std::vector<double>>& home) {
  static const char* const formats[] = {"krl", "rapid", "urscript", "fanuc", "val3", "gcode", "csv"};
  if (std::find(std::begin(formats), std::end(formats), format) == std::end(formats)) {
    throw Error("format: " + format + " not in {krl, rapid, urscript, fanuc, val3, gcode, csv}");
  }
  if (preferred_x.size() != 3) throw Error("preferred_x: give three numbers x, y, z");
  Inputs inputs;
  ExportJobOptions o;
  // One path file or several, in program order (the CLI's repeated --path).
  if (py::isinstance<py::list>(path) || py::isinstance<py::tuple>(path)) {
    for (const py::handle item : path) o.path_csvs.push_back(path_of(py::reinterpret_borrow<py::object>(item)));
    if (o.path_csvs.empty()) throw Error("path: give at least one path file");
  } else {
    o.path_csvs.push_back(path_of(path));
  }
  o.format = format;
  o.out_path = path_of(out);
  o.frame_path = inputs.transform(frame, "frame");
  o.frames.roll_cone_rad = roll_cone_deg / 180.0 * 3.141592653589793;
  o.frames.preferred_x = Eigen::Vector3d(preferred_x[0], preferred_x[1], preferred_x[2]);
  o.program.speed_mm_s = speed_mm_s;
  o.program.approach_speed_mm_s = approach_speed_mm_s;
  o.program.approach_mm = approach_mm;
  o.program.name = name;
  o.program.tool = tool;
  o.program.work_object = work_object;
  o.program.max_points = max_points;
  o.program.five_axis = !three_axis;
  o.program.blend_mm = blend_mm;
  o.program.process_on = process_on;
  o.program.process_off = process_off;
  if (home) {
    if (home->size() != 6) throw Error("home: give six joint angles J1, ..., J6 in degrees");
    o.program.home_deg = *home;
  }
  check_export_name(o);
  std::vector<std::string> inputs_read = o.path_csvs;
  inputs_read.push_back(o.frame_path);
  CallFiles files(inputs_read, std::vector<std::string>{o.out_path});  // the part files too, when staged
  const ExportJobResult result = [&] {
    py::gil_scoped_release release;
    return run_export(o);
  }();
  files.commit();
  py::dict arrays;
  arrays["warnings"] = py::cast(export_warnings(result));
  return answer(export_json(o, result), arrays);
}

py::tuple job_generate_eroded(const py::object& out, int rows, int cols, double length, double width,
                              double chord_radius, double span_radius, double twist,
                              const std::optional<std::vector<std::vector<double>>>& craters,
                              const std::vector<std::vector<double>>& bumps, double reference_offset,
                              double reference_tilt_deg, double noise, std::uint64_t seed) {
  GenerateErodedOptions options;
  ErodedOptions& o = options.eroded;
  o.rows = rows;
  o.cols = cols;
  o.length_mm = length;
  o.width_mm = width;
  o.chord_radius_mm = chord_radius;
  o.span_radius_mm = span_radius;
  o.twist_per_mm = twist;
  if (craters) {
    o.craters.clear();
    for (const std::vector<double>& c : *craters) o.craters.push_back(eroded_crater(c));
  }
  for (const std::vector<double>& b : bumps) o.bumps.push_back(eroded_bump(b));
  o.reference_offset_mm = reference_offset;
  o.reference_tilt_deg = reference_tilt_deg;
  o.noise_mm = noise;
  o.seed = seed;
  options.out_path = path_of(out);
  CallFiles files({}, {options.out_path});
  const GenerateErodedResult result = [&] {
    py::gil_scoped_release release;
    return run_generate_eroded(options);
  }();
  files.commit();
  return answer(generate_eroded_json(options, result), py::dict());
}

py::tuple job_generate_profile(const py::object& out, double length, double width, double bow, double bow_asymmetry,
                               double bow_out, double twist_deg, double kink_deg, double kink_at, double kink_length,
                               double spacing, double noise, double dropouts, bool second_edge, int holes,
                               double hole_radius, double hole_tx, bool marking_line, int outliers, double outlier_mm,
                               const std::vector<double>& offset, bool reverse, std::uint64_t seed) {
  if (offset.size() != 3) throw Error("offset: give three numbers x, y, z");
  GenerateProfileRequest r;
  ProfileDeformationOptions& d = r.scan.deformation;
  d.length_mm = length;
  d.width_mm = width;
  d.bow_in_plane_mm = bow;
  d.bow_asymmetry = bow_asymmetry;
  d.bow_out_of_plane_mm = bow_out;
  d.kink_at_mm = kink_at;
  d.kink_length_mm = kink_length;
  r.twist_deg = twist_deg;
  r.kink_deg = kink_deg;
  r.scan.spacing_mm = spacing;
  r.scan.noise_mm = noise;
  r.scan.dropout_fraction = dropouts;
  r.scan.second_edge = second_edge;
  r.scan.holes = holes;
  r.scan.hole_radius_mm = hole_radius;
  r.scan.hole_tx_mm = hole_tx;
  r.scan.marking_line = marking_line;
  r.scan.outliers = outliers;
  r.scan.outlier_mm = outlier_mm;
  r.offset_mm = Eigen::Vector3d(offset[0], offset[1], offset[2]);
  r.scan.reversed = reverse;
  r.scan.seed = seed;
  r.out_path = path_of(out);
  const GenerateProfileOptions options = generate_profile_options(r);
  CallFiles files({}, {r.out_path});
  const GenerateProfileResult result = [&] {
    py::gil_scoped_release release;
    return run_generate_profile(options);
  }();
  files.commit();
  return answer(generate_profile_json(result), py::dict());
}

py::tuple job_pose_error(const py::object& a, const py::object& b, const std::string& units) {
  Inputs inputs;
  PoseErrorOptions options;
  options.path_a = inputs.transform(a, "transform_a");
  options.path_b = inputs.transform(b, "transform_b");
  options.mm_per_unit = millimetres_per_unit(units);
  const PoseErrorResult result = run_pose_error(options);
  std::vector<std::string> in_memory;
  if (inputs.in_memory(options.path_a)) in_memory.push_back("transform_a");
  if (inputs.in_memory(options.path_b)) in_memory.push_back("transform_b");
  return answer(pose_error_json(options, result), py::dict(), in_memory);
}

py::tuple job_fit_cylinder(const py::object& input, double threshold, double min_radius,
                           std::optional<double> max_radius, std::optional<std::vector<double>> axis,
                           double axis_tolerance_deg, int normals_k, std::uint64_t seed, double max_shape_ambiguity,
                           const std::string& points, std::size_t surface_samples, const py::object& out,
                           const py::object& cad_deflection, const py::object& cad_angle_deg,
                           const py::object& cad_save_mesh, const py::object& report,
                           const py::object& progress_callback) {
  const std::string report_path = report_path_of(report);
  if (points != "auto" && points != "vertices" && points != "surface") {
    throw Error("points: " + points + " not in {auto, vertices, surface}");
  }
  Inputs inputs;
  FitCylinderJobOptions options;
  set_cad_options(cad_deflection, cad_angle_deg, cad_save_mesh, options.cad);
  options.input_path = inputs.geometry(input, "input");
  options.fit.threshold_mm = threshold;
  options.fit.min_radius_mm = min_radius;
  if (max_radius) options.fit.max_radius_mm = *max_radius;
  if (axis) {
    if (axis->size() != 3) throw Error("axis: give three numbers x, y, z");
    options.fit.axis_prior = Eigen::Vector3d((*axis)[0], (*axis)[1], (*axis)[2]);
    if (!(options.fit.axis_prior.norm() > 0.0)) throw Error("axis: the direction is zero");
  }
  options.fit.axis_prior_tolerance_rad = axis_tolerance_deg / 180.0 * 3.141592653589793;
  options.fit.normal_neighbors = normals_k;
  options.fit.seed = seed;
  options.fit.max_shape_ambiguity_mm = max_shape_ambiguity;
  options.points = points == "vertices"  ? CylinderPoints::kVertices
                   : points == "surface" ? CylinderPoints::kSurface
                                         : CylinderPoints::kAuto;
  options.surface_samples = surface_samples;
  options.out_path = path_of(out);
  options.keep_geometry = !report_path.empty();
  const Progress progress(progress_callback);
  options.fit.progress = progress.function();
  CallFiles files({options.input_path}, {options.out_path, report_path, options.cad.save_mesh_path});
  FitCylinderJobResult result = released(progress, [&] { return run_fit_cylinder(options); });
  const nlohmann::json j = fit_cylinder_json(result);
  if (!report_path.empty()) write_report(report_path, fit_cylinder_report(options, result, j, ""));
  files.commit();
  std::vector<std::uint8_t> inlier(result.points, 0);
  for (int i : result.fit.inliers) inlier[static_cast<std::size_t>(i)] = 1;
  py::dict arrays;
  arrays["warnings"] = py::cast(result.warnings);
  arrays["inlier"] = owned(std::move(inlier)).attr("astype")("bool");
  return answer(j, arrays,
                inputs.in_memory(options.input_path) ? std::vector<std::string>{"input"} : std::vector<std::string>{});
}

py::tuple job_saddle(double R, double r, double right_angle_pose_deg, double pitch_deg, double offset,
                     std::optional<double> step_deg, std::optional<double> speed, std::optional<double> period,
                     const py::object& out, const py::object& report) {
  const std::string report_path = report_path_of(report);
  SaddleRequest request;
  request.leg_radius_mm = R;
  request.pipe_radius_mm = r;
  request.pitch_deg = pitch_deg;
  request.offset_mm = offset;
  request.right_angle_pose_deg = right_angle_pose_deg;
  if (step_deg && (speed || period)) throw Error("saddle: give --step-deg or --speed with --period, not both");
  if (speed.has_value() != period.has_value()) throw Error("saddle: --speed and --period go together");
  request.step_deg = step_deg;
  request.speed_mm_per_s = speed;
  request.period_s = period;
  request.out_path = path_of(out);
  const SaddleJobOptions options = saddle_job_options(request);
  CallFiles files({}, {request.out_path, report_path});
  SaddleJobResult result = [&] {
    py::gil_scoped_release release;
    return run_saddle(options);
  }();
  const nlohmann::json j = saddle_json(request, result);
  if (!report_path.empty()) write_report(report_path, saddle_report(request, options, result));
  files.commit();
  std::vector<double> theta, pose, step;
  std::vector<Eigen::Vector3d> position;
  for (const SaddlePoint& p : result.saddle.points) {
    theta.push_back(p.theta_rad);
    position.push_back(p.position);
    pose.push_back(p.pose_rad);
    step.push_back(p.step_mm);
  }
  py::dict arrays;
  arrays["theta_rad"] = owned(std::move(theta));
  arrays["position_mm"] = owned(std::move(position));
  arrays["pose_rad"] = owned(std::move(pose));
  arrays["step_mm"] = owned(std::move(step));
  return answer(j, arrays);
}

}  // namespace
}  // namespace conform::python

PYBIND11_MODULE(_conform, m) {
  using namespace conform;
  using namespace conform::python;
  using py::arg;
  m.doc() = "conform's jobs (the CLI's pipelines); use the `conform` package, which wraps this module";
  // conform.Error (a ValueError) with the message as a Python caller reads it (inputs.h, for_python).
  static py::exception<Error> error_type(m, "Error", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const Error& e) {
      error_type(for_python(e.what()).c_str());
    }
  });

  py::class_<Geometry, std::shared_ptr<Geometry>>(m, "Geometry", "A mesh or cloud as read: mm, views, not copies")
      .def_property_readonly("points",
                             [](py::object self) { return rows_view(self, self.cast<Geometry&>().mesh.vertices); })
      .def_property_readonly("normals",
                             [](py::object self) { return rows_view(self, self.cast<Geometry&>().mesh.normals); })
      .def_property_readonly("faces",
                             [](py::object self) { return faces_view(self, self.cast<Geometry&>().mesh.faces); })
      .def_readonly("warnings", &Geometry::warnings)
      .def_readonly("path", &Geometry::path)
      .def("__len__", [](const Geometry& g) { return g.mesh.vertices.size(); })
      .def("__repr__", [](const Geometry& g) {
        return "<conform.Geometry " + std::to_string(g.mesh.vertices.size()) + " points, " +
               std::to_string(g.mesh.faces.size()) + " faces, normals: " + (g.mesh.has_normals() ? "yes" : "no") + ">";
      });

  m.def("read", &job_read, arg("path"), arg("units") = "mm", py::kw_only(), arg("cad_deflection") = py::none(),
        arg("cad_angle_deg") = py::none());
  m.def("compare", &job_compare, arg("scan"), arg("reference"), py::kw_only(), arg("transform") = py::none(),
        arg("tolerance") = CompareOptions{}.tolerance_mm, arg("out_deviation") = py::none(),
        arg("out_histogram") = py::none(), arg("units") = "mm", arg("scan_units") = py::none(),
        arg("reference_units") = py::none(), arg("flat_facets") = false,
        arg("cad_deflection") = py::none(), arg("cad_angle_deg") = py::none(), arg("cad_save_mesh") = py::none(),
        arg("report") = py::none(), arg("progress") = py::none());
  const AlignOptions align;
  m.def("align", &job_align, arg("scan"), arg("reference"), py::kw_only(), arg("method") = "", arg("init") = "none",
        arg("max_distance") = align.max_distance_mm, arg("overlap") = align.overlap,
        arg("max_iterations") = align.max_iterations, arg("free_tolerance_mm") = align.free_tolerance_mm,
        arg("free_tolerance_deg") = align.free_tolerance_deg, arg("pose_tolerance_mm") = align.pose_tolerance_mm,
        arg("tolerance") = align.tolerance_mm, arg("max_noise_ratio") = align.max_noise_ratio, arg("units") = "mm",
        arg("scan_units") = py::none(), arg("reference_units") = py::none(), arg("out_transform") = py::none(), arg("out_aligned") = py::none(), arg("cad_deflection") = py::none(),
        arg("cad_angle_deg") = py::none(), arg("cad_save_mesh") = py::none(), arg("report") = py::none(),
        arg("progress") = py::none());
  const ProgramOptions program;
  m.def("export", &job_export, arg("path"), py::kw_only(), arg("format"), arg("out"), arg("frame") = py::none(),
        arg("speed_mm_s") = program.speed_mm_s, arg("approach_speed_mm_s") = program.approach_speed_mm_s,
        arg("approach_mm") = program.approach_mm, arg("name") = "", arg("tool") = program.tool,
        arg("work_object") = program.work_object, arg("max_points") = program.max_points, arg("three_axis") = false,
        arg("roll_cone_deg") = 0.0, arg("preferred_x") = std::vector<double>{1.0, 0.0, 0.0},
        arg("blend_mm") = program.blend_mm, arg("process_on") = "", arg("process_off") = "", arg("home") = py::none());
  const ErodedOptions eroded;
  m.def("generate_eroded", &job_generate_eroded, arg("out"), py::kw_only(), arg("rows") = eroded.rows,
        arg("cols") = eroded.cols, arg("length") = eroded.length_mm, arg("width") = eroded.width_mm,
        arg("chord_radius") = eroded.chord_radius_mm, arg("span_radius") = eroded.span_radius_mm,
        arg("twist") = eroded.twist_per_mm, arg("crater") = py::none(),
        arg("bump") = std::vector<std::vector<double>>{}, arg("reference_offset") = eroded.reference_offset_mm,
        arg("reference_tilt_deg") = eroded.reference_tilt_deg, arg("noise") = eroded.noise_mm,
        arg("seed") = eroded.seed);
  const ProfileScanOptions profile;
  const ProfileDeformationOptions& bend = profile.deformation;
  m.def("generate_profile", &job_generate_profile, arg("out"), py::kw_only(), arg("length") = bend.length_mm,
        arg("width") = bend.width_mm, arg("bow") = bend.bow_in_plane_mm, arg("bow_asymmetry") = bend.bow_asymmetry,
        arg("bow_out") = bend.bow_out_of_plane_mm, arg("twist_deg") = 0.0, arg("kink_deg") = 0.0,
        arg("kink_at") = bend.kink_at_mm, arg("kink_length") = bend.kink_length_mm, arg("spacing") = profile.spacing_mm,
        arg("noise") = profile.noise_mm, arg("dropouts") = profile.dropout_fraction,
        arg("second_edge") = profile.second_edge, arg("holes") = profile.holes,
        arg("hole_radius") = profile.hole_radius_mm, arg("hole_tx") = profile.hole_tx_mm,
        arg("marking_line") = profile.marking_line, arg("outliers") = profile.outliers,
        arg("outlier_mm") = profile.outlier_mm, arg("offset") = std::vector<double>{0.0, 0.0, 0.0},
        arg("reverse") = profile.reversed, arg("seed") = profile.seed);
  m.def("pose_error", &job_pose_error, arg("transform_a"), arg("transform_b"), py::kw_only(), arg("units") = "mm");
  const FitCylinderJobOptions cylinder;
  m.def("fit_cylinder", &job_fit_cylinder, arg("input"), py::kw_only(), arg("threshold") = cylinder.fit.threshold_mm,
        arg("min_radius") = cylinder.fit.min_radius_mm, arg("max_radius") = py::none(), arg("axis") = py::none(),
        arg("axis_tolerance_deg") = 10.0, arg("normals_k") = cylinder.fit.normal_neighbors,
        arg("seed") = cylinder.fit.seed, arg("max_shape_ambiguity") = cylinder.fit.max_shape_ambiguity_mm,
        arg("points") = to_string(cylinder.points), arg("surface_samples") = cylinder.surface_samples,
        arg("out") = py::none(), arg("cad_deflection") = py::none(), arg("cad_angle_deg") = py::none(),
        arg("cad_save_mesh") = py::none(), arg("report") = py::none(), arg("progress") = py::none());
  const SaddleRequest saddle_defaults;
  m.def("saddle", &job_saddle, py::kw_only(), arg("R"), arg("r"), arg("right_angle_pose_deg"),
        arg("pitch_deg") = saddle_defaults.pitch_deg, arg("offset") = saddle_defaults.offset_mm,
        arg("step_deg") = py::none(), arg("speed") = py::none(), arg("period") = py::none(), arg("out") = py::none(),
        arg("report") = py::none());
  bind_toolpath_jobs(m);
  bind_generator_jobs(m);
  bind_inspect_job(m);
}
