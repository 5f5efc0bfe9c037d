// conform._conform's generators of sicp's and tube-joint's test data: generate_plate, generate_nosecone (`conform
// generate plate|nosecone`) and generate_tube_joint.
// Keyword arguments are the CLI's flags; unset ones keep the Options' or Request's defaults.

#include <algorithm>
#include <array>
#include <string>
#include <type_traits>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "conform/pipelines/generate/generate_panel_json.h"
#include "conform/pipelines/generate/generate_tube_joint_json.h"

namespace conform::python {
namespace {

py::tuple job_generate_panel(PanelShape shape, const py::object& out, const py::kwargs& kw) {
  const bool plate = shape == PanelShape::kPlate;
  const char* job = plate ? "generate_plate" : "generate_nosecone";
  static const std::vector<std::string> plate_keys = {"radius_x", "radius_y", "porthole_width", "porthole_height",
                                                       "round", "clamp_span", "sag", "bend", "twist", "opening",
                                                       "corner_radius"};
  static const std::vector<std::string> nosecone_keys = {"radius",        "window_height", "window_bottom",
                                                          "window_top",    "corner_radius", "ovality",
                                                          "droop"};
  const std::vector<std::string>& own = plate ? plate_keys : nosecone_keys;
  py::kwargs rest;  // the shape's own keys taken out: the others must be common ones
  for (const auto& item : kw) {
    if (std::find(own.begin(), own.end(), std::string(py::str(item.first))) == own.end()) {
      rest[item.first] = item.second;
    }
  }
  check_keywords(job, rest,
                 {"band", "thickness", "surface_edge", "contour_spacing", "trajectory_spacing", "scan_points", "noise",
                  "missing", "missing_patches", "missing_depth", "holes", "hole_radius", "field", "field_wavelength",
                  "seed", "progress"});
  const auto take = [&kw](const char* name) {
    return kw.contains(name) ? py::object(kw[name]) : py::object(py::none());
  };
  const auto set = [&take](const char* name, auto& field) {
    const py::object v = take(name);
    if (!v.is_none()) field = v.cast<std::remove_reference_t<decltype(field)>>();
  };
  GeneratePanelOptions options;
  PanelOptions& o = options.panel;
  o.shape = shape;
  options.out_path = path_of(out);
  if (plate) {
    set("radius_x", o.plate_radius_x_mm);
    set("radius_y", o.plate_radius_y_mm);
    set("porthole_width", o.porthole_width_mm);
    set("porthole_height", o.porthole_height_mm);
    set("round", o.round);
    set("clamp_span", o.clamp_span_mm);
    set("sag", o.sag_mm);
    set("bend", o.bend_mm);
    set("twist", o.twist_mm);
    std::string opening = "ellipse";
    set("opening", opening);
    o.opening = plate_opening(opening);
  } else {
    set("radius", o.barrel_radius_mm);
    set("window_height", o.window_height_mm);
    set("window_bottom", o.window_bottom_mm);
    set("window_top", o.window_top_mm);
    set("ovality", o.ovality_mm);
    set("droop", o.droop_mm);
  }
  set("corner_radius", o.corner_radius_mm);
  set("band", o.band_mm);
  set("thickness", o.thickness_mm);
  set("surface_edge", o.surface_edge_mm);
  set("contour_spacing", o.contour_spacing_mm);
  set("trajectory_spacing", o.trajectory_spacing_mm);
  set("scan_points", o.scan_points);
  set("noise", o.noise_mm);
  set("missing", o.missing_fraction);
  set("missing_patches", o.missing_patches);
  set("missing_depth", o.missing_depth_mm);
  set("holes", o.holes);
  set("hole_radius", o.hole_radius_mm);
  set("field", o.field_mm);
  set("field_wavelength", o.field_wavelength_mm);
  set("seed", o.seed);
  const Progress progress(take("progress"));
  o.progress = progress.function();
  CallFiles files({}, {options.out_path});
  const GeneratePanelResult result = released(progress, [&] { return run_generate_panel(options); });
  files.commit();
  return answer(generate_panel_json(result), py::dict());
}

py::tuple job_generate_tube_joint(const py::object& out_leg, const py::object& out_stub, const py::object& out_truth,
                                  const py::kwargs& kw) {
  check_keywords("generate_tube_joint", kw,
                 {"pitch_deg", "offset", "protrusion", "leg_radius", "stub_radius", "wall", "edge", "leg_vertices",
                  "stub_vertices", "ovality_pct", "peaking", "leg_seam_deg", "stub_seam_deg", "seam_width", "leg_bump",
                  "stub_bump", "noise", "leg_arc_deg", "stub_length", "truth_points", "seed", "ascii"});
  const auto set = [&kw](const char* name, auto& field) {
    if (kw.contains(name) && !kw[name].is_none()) field = kw[name].cast<std::remove_reference_t<decltype(field)>>();
  };
  GenerateTubeJointRequest r;
  GenerateTubeJointOptions& job = r.job;
  job.leg_path = path_of(out_leg);
  job.stub_path = path_of(out_stub);
  job.truth_path = path_of(out_truth);
  set("pitch_deg", r.pitch_deg);
  set("offset", job.spec.offset_mm);
  set("protrusion", job.spec.protrusion_mm);
  set("leg_radius", job.joint.leg.radius_mm);
  set("stub_radius", job.stub_outer_radius_mm);
  set("wall", job.wall_mm);
  set("edge", r.edge_mm);
  set("leg_vertices", job.joint.leg.vertex_count);
  set("stub_vertices", job.joint.stub.vertex_count);
  set("ovality_pct", r.ovality_pct);
  set("peaking", r.peaking_mm);
  set("leg_seam_deg", r.leg_seam_deg);
  set("stub_seam_deg", r.stub_seam_deg);
  set("seam_width", r.seam_width_mm);
  set("leg_bump", r.leg_bumps);
  set("stub_bump", r.stub_bumps);
  set("noise", r.noise_mm);
  set("leg_arc_deg", r.leg_arc_deg);
  set("stub_length", job.joint.stub_length_mm);
  set("truth_points", job.joint.truth_points);
  set("seed", r.seed);
  set("ascii", r.ascii);
  const GenerateTubeJointOptions options = generate_tube_joint_options(r);
  CallFiles files({}, {job.leg_path, job.stub_path, job.truth_path});
  const GenerateTubeJointResult result = [&] {
    py::gil_scoped_release release;
    return run_generate_tube_joint(options);
  }();
  files.commit();
  return answer(generate_tube_joint_json(options, result), py::dict());
}

}  // namespace

void bind_generator_jobs(py::module_& m) {
  m.def(
      "generate_plate",
      [](const py::object& out, const py::kwargs& kw) { return job_generate_panel(PanelShape::kPlate, out, kw); },
      py::arg("out"));
  m.def(
      "generate_nosecone",
      [](const py::object& out, const py::kwargs& kw) { return job_generate_panel(PanelShape::kNoseCone, out, kw); },
      py::arg("out"));
  // Keyword arguments as the flags of `conform generate tube-joint` (GenerateTubeJointRequest holds their defaults).
  m.def("generate_tube_joint", &job_generate_tube_joint, py::arg("out_leg"), py::arg("out_stub"), py::arg("out_truth"));
}

}  // namespace conform::python
