// `conform tube-joint`: cutting and welding paths for a tubular joint from a leg scan (outer surface, leg frame) and
// a stub scan (inner surface, stub frame) — Lind & Ystgaard (2020), pipelines/tube_joint/tube_joint.h.

#include <cstdio>
#include <string>
#include <vector>

#include "cad_options.h"
#include "command.h"
#include "conform/core/error.h"
#include "conform/pipelines/tube_joint/tube_joint.h"
#include "conform/pipelines/tube_joint/tube_joint_json.h"
#include "conform/pipelines/tube_joint/tube_joint_report.h"
#include "number_list.h"
#include "report_option.h"
#include "terminal.h"

namespace conform::app {
namespace {

std::array<double, 4> parse_groove_deg(const std::string& text) {
  const std::vector<double> v = parse_numbers(text, 4, "--groove-deg", "toe,side,heel,side in degrees");
  return {v[0], v[1], v[2], v[3]};
}

// CSV `phi_deg,alpha_deg`: the groove table of Eq. (5), generalised.
std::vector<double> parse_walls(const std::string& text) {
  const bool two = text.find(',') != std::string::npos;
  const std::vector<double> v = parse_numbers(text, two ? 2 : 1, "--wall-thickness", "MM or LEG_MM,STUB_MM");
  for (const double d : v) {
    if (!(d > 0.0)) throw Error("--wall-thickness " + text + ": wall thicknesses must be > 0 mm");
  }
  return two ? v : std::vector<double>{v[0], v[0]};
}

class TubeJointCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.add_option("--leg", o_.leg_path, "Leg outer-surface mesh, in the leg frame L (.ply .stl .obj); required")
        ->required();
    c.add_option("--stub", o_.stub_path, "Stub inner-surface mesh, in the stub frame S (.ply .stl .obj); required")
        ->required();
    CLI::Option* pitch = c.add_option("--pitch-deg", pitch_deg_,
                                      "Angle between the leg and stub axes, deg, (0, 90]; required unless --leg-pose");
    CLI::Option* offset = c.add_option("--offset", o_.spec.offset_mm, "Distance between the axes along y_L, mm");
    CLI::Option* protrusion = c.add_option("--protrusion", o_.spec.protrusion_mm,
                                           "Stub's distal end to the leg axis along the stub axis, mm, > 0; required "
                                           "unless --leg-pose");
    CLI::Option* pose = c.add_option("--leg-pose", o_.leg_pose_path,
                                     "4x4 text T_S_L (leg coordinates into the stub frame) instead of the three above");
    pose->excludes(pitch)->excludes(offset)->excludes(protrusion);
    c.add_option("--leg-markers", o_.leg_markers_path,
                 "CSV x_mm,y_mm,z_mm,ref_x_mm,ref_y_mm,ref_z_mm: >= 3 leg markers in the scan and in L; the leg's "
                 "frame then comes from its cylinder fit + markers; default none (the mesh is in L)");
    c.add_option("--stub-markers", o_.stub_markers_path,
                 "The same for the stub (known positions in S); default none (the mesh is in S)");
    c.add_option("--marker-tolerance", o_.marker_tolerance_mm,
                 "Largest distance of a registered marker from its known position, mm; farther is bad input");
    c.add_option("--backtrack-tolerance", o_.solve.backtrack_tolerance_mm,
                 "Largest step back in azimuth let pass along the intersection (arc on the stub), mm; < 0: "
                 "automatic, 0.5 edge + 6 noise of the scans near the seam");
    c.add_option("--max-facet-error", o_.solve.max_facet_error_mm,
                 "Largest seam error the meshes' facets alone may cause, (s_leg + s_stub) / sin(crossing angle), mm; "
                 "coarser meshes exit 1");
    c.add_option("--island-ratio", o_.solve.max_island_ratio,
                 "Intersection loops shorter than this fraction of the longest are dropped as noise islands; "
                 "longer ones fail");
    c.add_option("--max-direction-error", o_.solve.max_direction_error_deg,
                 "Largest 2-sigma error of the seam tangent the scans' noise may leave, deg; beyond: exit 1 "
                 "[directions]");
    c.add_option("--weld-tolerance", o_.solve.weld_edge_fraction,
                 "Vertices closer than this fraction of a mesh's median edge length are welded into one (unwelded "
                 "scanner meshes); 0 = only coincident ones")
        ->check(CLI::Range(0.0, 0.25));
    c.add_option("--wall-thickness", walls_,
                 "Wall thickness, mm: one value for both, or LEG_MM,STUB_MM; checks every tool tip and approach line "
                 "against the walls (exit 1 when a tool is inside material)");
    CLI::Option* step_deg = c.add_option("--step-deg", step_deg_, "Resample at equal azimuth steps, deg");
    CLI::Option* step_mm = c.add_option("--step-mm", step_mm_, "Resample at equal arc-length steps instead, mm");
    step_deg->excludes(step_mm);
    CLI::Option* smoothing = c.add_option(
        "--smoothing", smoothing_mm2_,
        "Closed smoothing cubic B-spline before resampling: target sum of squared residuals, mm^2 (splprep's s); "
        "default none");
    CLI::Option* smoothing_rms =
        c.add_option("--smoothing-rms", smoothing_rms_mm_, "Smoothing target as RMS per intersection point, mm");
    smoothing->excludes(smoothing_rms);
    CLI::Option* groove =
        c.add_option("--groove-deg", groove_, "Groove (cut) angle at toe,side,heel,side, deg, [0, 90)");
    c.add_option("--groove-table", groove_table_,
                 "CSV phi_deg,alpha_deg: groove angles at any azimuths (Eq. 5), instead of --groove-deg")
        ->excludes(groove);
    c.add_option("--groove-interpolation", interpolation_, "linear, quadratic or spline (periodic cubic) (Eq. 5)")
        ->check(CLI::IsMember({"linear", "quadratic", "spline"}));
    c.add_option("--weld-angle-deg", weld_deg_, "Weld torch angle off the leg surface, deg, [0, 90)");
    c.add_option("--cut-standoff", o_.solve.tools.cut_standoff_mm, "Cutting tool standoff s_c, mm");
    c.add_option("--weld-standoff", o_.solve.tools.weld_standoff_mm, "Welding torch standoff s_w, mm");
    c.add_option("--k-normals", o_.solve.geometry.k_normals,
                 "Vertices per normal fit (PCA plane + quadric), >= 3; 0 = sized to each mesh's noise and edges");
    c.add_option("--k-refine", o_.solve.geometry.k_refine,
                 "Vertices per local surface fit when refining path points onto both scans; 0 = off (the paper's "
                 "point)");
    c.add_option("--out-path", o_.out_path,
                 "CSV: phi_rad,x_mm,y_mm,z_mm,tx,ty,tz,nsx,nsy,nsz,nlx,nly,nlz (stub frame)");
    c.add_option("--out-cut", o_.out_cut, "CSV: phi_rad,x_mm,y_mm,z_mm,dx,dy,dz cutting poses");
    c.add_option("--out-weld", o_.out_weld, "CSV: phi_rad,x_mm,y_mm,z_mm,dx,dy,dz welding poses");
    add_report_option(c, report_);
    add_cad_options(c, o_.cad);
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
    c.add_flag("--quiet", quiet_, "No progress on stderr");
    step_mm_option_ = step_mm;
    pitch_ = pitch;
    protrusion_ = protrusion;
  }

  void declare_files(OutputSet& files) override {
    files.add_inputs(
        {o_.leg_path, o_.stub_path, o_.leg_pose_path, o_.leg_markers_path, o_.stub_markers_path, groove_table_});
    files.add_outputs({o_.out_path, o_.out_cut, o_.out_weld, o_.cad.save_mesh_path, report_});
  }

  int run() override {
    TubeJointRequest request;
    request.job = o_;
    if (pitch_->count() > 0) request.pitch_deg = pitch_deg_;
    request.protrusion_given = protrusion_->count() > 0;
    request.step_deg = step_deg_;
    if (step_mm_option_->count() > 0) request.step_mm = step_mm_;
    request.smoothing_mm2 = smoothing_mm2_;
    request.smoothing_rms_mm = smoothing_rms_mm_;
    if (!groove_.empty()) request.groove_deg = parse_groove_deg(groove_);
    request.groove_table_path = groove_table_;
    request.interpolation = interpolation_;
    if (!walls_.empty()) request.walls_mm = parse_walls(walls_);
    request.weld_angle_deg = weld_deg_;
    TubeJointJobOptions o = tube_joint_job_options(request);
    o.solve.progress = stderr_progress(quiet_ || json_);
    o.cad.progress = o.solve.progress;
    o.keep_geometry = !report_.empty();
    const TubeJointJobResult r = run_tube_joint(o);
    const TubeJointSolution& s = r.solution;
    if (json_) {
      print_json(tube_joint_json(r));
    } else {
      print_cad_text(r.cad_inputs);
      print_text(r);
    }
    if (!report_.empty()) {
      html::Page page = tube_joint_report(o, r);
      page.date = report_date();
      write_report(report_, page);
    }
    for (const std::string& w : s.warnings) warn("tube-joint: " + w);
    if (!s.ok && s.check.condition == "safety") {
      warn("tube-joint: a tool would stand inside material: " + s.termination + "; no file written");
      return 1;
    }
    if (!s.ok && s.check.condition == "coarse") {
      warn("tube-joint: the scans are too coarse for a path: " + s.termination + "; no file written");
      return 1;
    }
    if (!s.ok) {
      warn("tube-joint: the intersection is not one closed curve the tool can follow: " + s.termination +
           "; no file written");
      return 1;
    }
    return 0;
  }

 private:
  static void print_text(const TubeJointJobResult& r) {
    const TubeJointSolution& s = r.solution;
    std::printf("meshes        leg %zu faces, stub %zu faces\n", r.leg_faces, r.stub_faces);
    for (const auto* residuals : {&r.leg_marker_residuals_mm, &r.stub_marker_residuals_mm}) {
      if (residuals->empty()) continue;
      const bool leg = residuals == &r.leg_marker_residuals_mm;
      const TubeReferenceResult& ref = leg ? r.leg_reference : r.stub_reference;
      std::printf("markers       %s (%s): residuals", leg ? "leg" : "stub", ref.method.c_str());
      for (const double d : *residuals) std::printf(" %.3f", d);
      std::printf(" mm; cylinder fit off by %.2f deg, %.2f mm\n", ref.axis_disagreement_deg, ref.axis_offset_mm);
    }
    std::printf("intersection  %zu segments, %zu curve vertices (%zu triangle pairs tested), %.3f s\n", s.segments,
                s.curve_vertices, s.candidate_pairs, s.intersection_seconds);
    if (!s.ok && s.check.condition == "safety") {
      std::printf("tools         NOT clear of the material: %s\n", s.termination.c_str());
      return;
    }
    if (!s.ok && s.check.condition == "coarse") {
      std::printf("scans         NOT fine enough: %s\n", s.termination.c_str());
      return;
    }
    if (!s.ok) {
      std::printf("curve         NOT a single closed curve: %s\n", s.termination.c_str());
      return;
    }
    std::printf("scans         noise leg %.3f stub %.3f mm, edge leg %.2f stub %.2f mm\n", s.leg_quality.noise_mm,
                s.stub_quality.noise_mm, s.leg_quality.edge_mm, s.stub_quality.edge_mm);
    std::printf(
        "curve         closed, one turn about the stub axis (%zu islands dropped; %zu vertices dropped as "
        "backtracking, largest %.3f mm, tolerance %.3f mm)\n",
        s.islands, s.dropped_vertices, s.max_backtrack_mm, s.backtrack_tolerance_mm);
    std::printf("path          %zu points (%zu refined), length %.3f mm, step min %.3f max %.3f mm%s\n",
                s.path.points.size(), s.refined_points, s.path.length_mm, s.path.min_step_mm, s.path.max_step_mm,
                s.path.smoothed ? ", smoothed" : "");
    std::printf("tools         %s\n", s.safety.walls_checked ? "clear of the walls (tips and approach lines checked)"
                                                             : "walls not checked (give --wall-thickness)");
    std::printf("time          %.3f s in all\n", s.total_seconds);
    for (const std::string& path : r.written) std::printf("wrote         %s\n", path.c_str());
  }

  TubeJointJobOptions o_;
  std::string report_;
  double pitch_deg_ = 90.0;
  double step_deg_ = 1.0;
  double step_mm_ = 5.0;
  double smoothing_mm2_ = -1.0;
  double smoothing_rms_mm_ = 0.0;
  std::string groove_;
  std::string groove_table_;
  std::string walls_;
  std::string interpolation_ = "linear";
  double weld_deg_ = 45.0;
  bool json_ = false;
  bool quiet_ = false;
  CLI::Option* step_mm_option_ = nullptr;
  CLI::Option* pitch_ = nullptr;
  CLI::Option* protrusion_ = nullptr;
};

}  // namespace

CONFORM_COMMAND(TubeJointCommand, "tube-joint",
                "Cutting and welding paths for a tubular joint from leg and stub scans (Lind & Ystgaard 2020)")

}  // namespace conform::app
