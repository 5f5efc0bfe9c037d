// `conform inspect`: a scan inspected face by face against its CAD (pipelines/inspect/inspect.h): per face the deviation,
// the form and the fitted feature against its nominal, as text or JSON, and optionally a CSV of the faces.

#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Geometry>

#include "cad_options.h"
#include "command.h"
#include "conform/core/constants.h"
#include "conform/core/units.h"
#include "conform/pipelines/inspect/inspect.h"
#include "conform/pipelines/inspect/inspect_json.h"
#include "conform/pipelines/inspect/inspect_report.h"
#include "report_option.h"
#include "terminal.h"

namespace conform::app {
namespace {


class InspectCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.description(
        "Inspection by the CAD's faces: each scan point assigned to the face it lies on; per face the signed "
        "deviation (+ outside, to the exact surface of planes, cylinders, cones, spheres and tori), the form "
        "(flatness, cylindricity) and the fitted feature against its nominal (a plane's normal, a cylinder's radius "
        "and axis)");
    c.add_option("--scan", options_.scan_path, "Scan, cloud or mesh (.ply .stl .obj .pcd .xyz .txt .asc .csv)")
        ->required();
    c.add_option("--reference", options_.reference_path, "The part's CAD: .step .stp .iges .igs")->required();
    c.add_option("--transform", options_.transform_path,
                 "T_ref_scan, 4x4 row-major text (e.g. from `conform align --out-transform`), applied to the scan; "
                 "default: the scan is already in the part frame");
    c.add_option("--align", align_, "best-fit: align the scan to the CAD first (conform align's defaults)")
        ->check(CLI::IsMember({"best-fit"}));
    c.add_option("--datums", options_.datum_faces,
                 "Datum faces A,B,C (face ids, primary first; 1 to 3): after the initial pose the scan is moved by the "
                 "3-2-1 datum fit and every figure is in the datum frame. A is a plane; B a plane (1 rotation, 1 "
                 "translation) or a cylinder square to A (its axis: 2 translations); C a plane or a cylinder (what is "
                 "left: a translation after two planes, the turn about B's axis after a cylinder)")
        ->delimiter(',');
    c.add_option("--max-distance", options_.max_distance_mm,
                 "A point farther than this from the CAD is on no face, mm; default 0: automatic, the larger of 0.5 "
                 "mm and 20 times the scan's noise");
    c.add_option("--max-normal-angle-deg", normal_angle_deg_,
                 "A point whose normal is farther than this from its face's is on no face, deg; default 30");
    c.add_option("--form-trim", options_.form_trim,
                 "Share of a face's residuals left out of its form zone, half at each end; default 0.01");
    c.add_option("--min-fit-points", options_.min_fit_points,
                 "Fewer points on a face: no feature fitted; default 30");
    c.add_option("--tolerances", options_.tolerances_path,
                 "Limits per face, .csv with columns face and any of lower_mm, upper_mm, form_mm, and for a hole or "
                 "boss (named by one of its faces) diameter_lower_mm, diameter_upper_mm, position_mm (an empty cell: "
                 "not toleranced): pass/fail per face and feature and a verdict; the exit code stays 0 when the job "
                 "ran");
    c.add_option("--out-faces", options_.out_faces_path, "Write one row per face as .csv");
    c.add_option("--units", units_, "Units of the scan and the transform (mm, cm, m, in); the CAD says its own");
    add_report_option(c, report_path_);
    add_cad_options(c, options_.cad);
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override {
    files.add_inputs(
        {options_.scan_path, options_.reference_path, options_.transform_path, options_.tolerances_path});
    files.add_outputs({options_.out_faces_path, options_.cad.save_mesh_path, report_path_});
  }

  int run() override {
    options_.mm_per_unit = millimetres_per_unit(units_);
    options_.best_fit = align_ == "best-fit";
    options_.max_normal_angle_rad = radians(normal_angle_deg_);
    options_.progress = stderr_progress(false);
    options_.cad.progress = options_.progress;
    options_.keep_geometry = !report_path_.empty();
    const InspectResult result = run_inspect(options_);
    warn_all(result.warnings);
    const nlohmann::json json = inspect_json(options_, result, units_);
    if (!report_path_.empty()) write_report(report_path_, inspect_report(options_, result, json, report_date()));
    if (json_) {
      print_json(json);
    } else {
      print_cad_text(result.cad_inputs);
      print_text(result);
      if (!report_path_.empty()) std::printf("wrote        %s\n", report_path_.c_str());
    }
    if (!result.ok) {
      warn(result.termination);
      return 1;
    }
    return 0;
  }

 private:
  void print_text(const InspectResult& r) const {
    std::printf("scan         %s (%zu points)\n", options_.scan_path.c_str(), r.scan_points);
    std::printf("alignment    %s\n", r.alignment == "transform" ? options_.transform_path.c_str()
                                                                 : r.alignment.c_str());
    if (!r.align_summary.empty()) std::printf("best fit     %s\n", r.align_summary.c_str());
    if (!options_.datum_faces.empty()) {
      std::printf("datums       faces");
      for (const std::size_t id : options_.datum_faces) std::printf(" %zu", id);
      std::printf(": turned %.4f deg from the initial pose, each moved along its normal by",
                  degrees(Eigen::AngleAxisd(r.T_datum_initial.linear()).angle()));
      for (const double m : r.datum_moved_mm) std::printf(" %.4f", m);
      std::printf(" mm\n");
    }
    if (r.faces.empty()) return;
    std::printf("assigned     %zu of %zu points; on no face: %zu beyond %.3g mm%s, %zu by their normal\n",
                r.assigned, r.scan_points, r.beyond_distance, r.max_distance_mm,
                r.max_distance_automatic ? " (automatic)" : "", r.normal_mismatch);
    std::printf("scan noise   %.4f mm\n", r.scan_noise_mm);
    std::printf("%4s %-9s %7s %9s %8s %9s %9s %8s  %s\n", "face", "type", "points", "mean_mm", "std_mm", "min_mm",
                "max_mm", "form_mm", "feature");
    for (const FaceInspection& f : r.faces) {
      if (f.points == 0) continue;
      std::printf("%4zu %-9s %7zu %9.4f %8.4f %9.4f %9.4f ", f.id, to_string(f.nominal.type), f.points,
                  f.deviation.mean_mm, f.deviation.std_mm, f.deviation.min_mm, f.deviation.max_mm);
      if (f.form_measured) {
        std::printf("%8.4f  ", f.form.width_mm);
      } else {
        std::printf("%8s  ", "-");
      }
      if (f.verdict) std::printf("%s ", !f.verdict->measured ? "NOT MEASURED" : f.verdict->pass ? "pass" : "FAIL");
      if (f.fitted && f.nominal.type == CadSurfaceType::kCylinder) {
        std::printf("radius %.4f (nominal %.4f), axis offset %.4f mm, %.3f deg\n", f.radius_mm, f.nominal.radius_mm,
                    f.axis_offset_mm, f.axis_angle_deg);
      } else if (f.fitted && f.nominal.type == CadSurfaceType::kSphere) {
        std::printf("radius %.4f (nominal %.4f), centre offset %.4f mm\n", f.radius_mm, f.nominal.radius_mm,
                    f.centre_offset_mm);
      } else if (f.fitted && f.nominal.type == CadSurfaceType::kCone) {
        std::printf("half-angle %.4f deg (nominal %.4f), axis offset %.4f mm\n", f.half_angle_deg,
                    degrees(f.nominal.half_angle_rad), f.axis_offset_mm);
      } else if (f.fitted && f.nominal.type == CadSurfaceType::kTorus) {
        std::printf("radii %.4f / %.4f (nominal %.4f / %.4f), centre offset %.4f mm\n", f.radius_mm,
                    f.minor_radius_mm, f.nominal.radius_mm, f.nominal.minor_radius_mm, f.centre_offset_mm);
      } else if (f.fitted && f.nominal.type == CadSurfaceType::kPlane) {
        std::printf("normal %.4f deg from nominal, offset %.4f mm\n", f.angle_to_nominal_deg, f.plane_offset_mm);
      } else {
        std::printf("%s\n", f.fit_note.c_str());
      }
    }
    for (const FeatureInspection& feature : r.features) {
      const FaceInspection& f = feature.measured;
      if (f.points == 0) continue;
      std::string faces;
      for (const std::size_t id : feature.faces) faces += (faces.empty() ? "" : "+") + std::to_string(id);
      std::printf("feature %zu   %s, faces %s, %zu points: ", feature.id, f.nominal.sense < 0 ? "hole" : "boss",
                  faces.c_str(), f.points);
      if (feature.verdict) {
        std::printf("%s ", !feature.verdict->measured ? "NOT MEASURED" : feature.verdict->pass ? "pass" : "FAIL");
      }
      if (f.fitted) {
        std::printf("diameter %.4f (nominal %.4f), position %.4f mm, cylindricity %.4f mm", 2.0 * f.radius_mm,
                    2.0 * f.nominal.radius_mm, f.position_mm, f.form.width_mm);
        if (std::isfinite(f.perpendicularity_mm)) std::printf(", perpendicularity %.4f mm", f.perpendicularity_mm);
        std::printf("\n");
      } else {
        std::printf("%s\n", f.fit_note.c_str());
      }
    }
    std::size_t unseen = 0;
    for (const FaceInspection& f : r.faces) unseen += f.points == 0 ? 1 : 0;
    std::printf("faces        %zu, of which %zu without scan points\n", r.faces.size(), unseen);
    if (!r.verdict.empty()) std::printf("verdict      %s (%s)\n", r.verdict.c_str(), options_.tolerances_path.c_str());
    if (!r.out_faces_path.empty()) std::printf("wrote        %s\n", r.out_faces_path.c_str());
  }

  InspectOptions options_;
  std::string align_;
  double normal_angle_deg_ = 30.0;
  std::string units_ = "mm";
  std::string report_path_;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(InspectCommand, "inspect",
                "Inspection by the CAD's faces: per-face deviation, form (flatness, cylindricity), feature size and "
                "position")

}  // namespace conform::app
