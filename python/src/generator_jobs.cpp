// conform._conform's panel generators: generate_plate and generate_nosecone (`conform generate plate|nosecone`).
// Keyword arguments are the CLI's flags; unset ones keep PanelOptions' defaults.

#include <algorithm>
#include <string>
#include <type_traits>
#include <vector>

#include "bindings.h"
#include "conform/pipelines/generate_panel_json.h"

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
  const GeneratePanelResult result = released(progress, [&] { return run_generate_panel(options); });
  return answer(generate_panel_json(result), py::dict());
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
}

}  // namespace conform::python
