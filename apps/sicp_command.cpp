// `conform sicp`: deburring on a deformed part. Maps the nominal trajectory onto the scanned part by
// Subdivision-ICP, one rigid transform or the projection model (pipelines/sicp/sicp.h) and writes it with the same rows.
// Exit code 1 when the registration did not converge or the path failed its checks (nothing is written then).

#include <cstdio>
#include <string>

#include "cad_options.h"
#include "command.h"
#include "conform/core/error.h"
#include "conform/pipelines/sicp/sicp.h"
#include "conform/pipelines/sicp/sicp_json.h"
#include "conform/pipelines/sicp/sicp_report.h"
#include "report_option.h"
#include "terminal.h"

namespace conform::app {
namespace {

class SicpCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.description("Map a deburring trajectory onto a deformed part: Subdivision-ICP (or rigid, or projection)");
    SicpCompensationOptions& o = options_.compensation;
    c.add_option("--contour", options_.contour_path,
                 "Nominal contour: CSV x_mm,y_mm,z_mm in order, or a mesh (.ply .stl .obj) whose boundary loop on the "
                 "scan is taken; required")
        ->required();
    c.add_option("--scan", options_.scan_path, "Scan of the deformed part, cloud or mesh, mm; required")->required();
    c.add_option("--trajectory", options_.trajectory_path,
                 "Nominal trajectory, CSV x_mm,y_mm,z_mm,nx,ny,nz (unit tool normals); required")
        ->required();
    c.add_option("--surface", options_.surface_path,
                 "Nominal surface around the contour (mesh: point-to-surface); required with a CSV contour (a mesh "
                 "contour is its own surface)");
    c.add_option("--segment-length", o.sicp.segmentation.segment_length_mm, "Longest segment (epsilon), mm");
    c.add_option("--overlap", o.sicp.segmentation.overlap,
                 "Overlap at each junction, share of the shorter segment, in (0, 1)");
    c.add_option("--curvature-radius", o.sicp.segmentation.curvature_radius_mm,
                 "Osculating radius below which a contour point is a corner (a segment boundary), mm; 0: none");
    c.add_option("--model", model_, "sicp, rigid or projection")->check(CLI::IsMember({"sicp", "rigid", "projection"}));
    c.add_option("--projection-fit", fit_, "The projection model's height field: parabola or spline")
        ->check(CLI::IsMember({"parabola", "spline"}));
    c.add_option("--neighbourhood", o.sicp.neighbourhood_mm, "Contour neighbourhood: scan within this, mm");
    c.add_option("--stability", o.sicp.stability_mm, "Stability region reaches this far from the contour, mm");
    c.add_option("--max-distance", o.sicp.max_distance_mm, "Pair distance of the segment ICPs, mm");
    c.add_option("--coarse-max-distance", o.sicp.coarse_max_distance_mm,
                 "Pair distance of the first rigid ICP (the scan is roughly in place), mm");
    c.add_option("--scan-voxel", o.sicp.scan_voxel_mm, "Scan thinned to one point per voxel, mm; 0: all");
    c.add_flag("--no-joint", no_joint_, "Segments registered independently (the paper), no joint refinement");
    c.add_option("--joint-weight", o.sicp.joint.weight,
                 "Weight of neighbouring segments' disagreement in the joint refinement");
    c.add_option("--joint-damping", o.sicp.joint.damping,
                 "Weight of each segment's slide along the edge in the joint refinement (holds a drift the data leave "
                 "free)");
    c.add_option("--max-iterations", o.sicp.max_iterations,
                 "Iteration limit of every ICP (rigid and segments); a fit that reaches it is kept and judged by its "
                 "residuals")
        ->check(CLI::Range(1, 1000));
    c.add_option("--min-edge-points", o.checks.min_edge_points,
                 "Scan points within the edge radius a row needs to be measured (and a segment's neighbourhood not "
                 "to be blind); 0: every row counts as measured");
    c.add_option("--edge-radius", o.checks.edge_radius_mm,
                 "Scan points within this of a compensated row measure the edge there, mm");
    c.add_option("--max-edge-gap", o.checks.max_edge_gap_mm,
                 "Longest stretch of path without scan of the edge that is bridged from the measured rows on both "
                 "sides (no corner in it), mm; longer: its rows are untrusted");
    c.add_option("--max-corner-gap", o.checks.max_corner_gap_mm,
                 "An unmeasured stretch over a corner is bridged when at most this long with 20 mm measured on both "
                 "sides, mm; 0: never");
    c.add_option("--max-edge-offset", o.checks.max_edge_offset_mm,
                 "Where the scan shows its own edge (no flank scanned), rows farther than this across from it are "
                 "untrusted, mm");
    c.add_option("--max-row-step", o.checks.max_row_step_mm,
                 "Rows whose correction changes by more than this from the row before (per mm of row spacing), or "
                 "that step back along the path, are untrusted, mm");
    c.add_option("--max-surface-offset", o.checks.max_surface_offset_mm,
                 "Rows where the scanned surface lies farther than this off the fitted model along the tool axis "
                 "(the plane of the face's residuals within 6 mm, significant at 5 standard errors: a dent, a bulge) "
                 "are untrusted, mm");
    c.add_option("--max-normal-error-deg", o.checks.max_normal_error_deg,
                 "Rows whose tool normal is more than this off the scanned surface's slope along the path "
                 "(significant at 5 standard errors) are untrusted, deg");
    c.add_option("--max-local-offset", o.checks.max_local_offset_mm,
                 "Rows where the scan within 4 mm lies farther than this off the model against the rows 8-16 mm "
                 "before and after (significant at 5 standard errors: a dent a few mm across) are untrusted, mm");
    c.add_option("--max-dent-slope-deg", o.checks.max_dent_slope_deg,
                 "Rows where a dent narrower than the plane's disc (a Gaussian bump fitted over a quadratic background "
                 "within 18 mm, significant at 5 standard errors) slopes more than this are untrusted, deg");
    c.add_option("--outlier-ratio", o.checks.outlier_ratio,
                 "A segment whose residual RMS exceeds this times the estimated noise is an outlier (untrusted)");
    c.add_option("--max-off-surface", o.checks.max_off_surface,
                 "A segment with more than this share of its scan points off the surface it was fitted to (beyond 4 "
                 "robust sigmas: a dent, a fixture) is an outlier (untrusted); stray points are left out of its RMS");
    c.add_option("--max-offset", o.checks.max_offset_mm,
                 "Trajectory rows farther than this from the contour are untrusted, mm");
    c.add_option("--normal-smoothing", o.normals.smooth_mm,
                 "Tool normals averaged along the path over this arc length, mm; 0: not smoothed");
    c.add_option(
         "--normals", normals_,
         "Tool normals: rotate (the nominal ones with the blended transforms) or scan (plane fitted around each point)")
        ->check(CLI::IsMember({"scan", "rotate"}));
    c.add_option("--truth", options_.truth_path,
                 "Ground-truth trajectory (same columns and rows): report the error against it");
    c.add_option("--out-trajectory", options_.out_trajectory_path,
                 "Write the compensated trajectory (CSV, same rows and order) when the registration converged");
    c.add_option("--out-rows", options_.out_rows_path,
                 "Write each row's correction (across the edge, along the tool axis, along the path, mm) and its "
                 "confidence (CSV), with the trajectory");
    add_report_option(c, report_path_);
    add_cad_options(c, options_.cad);
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
    c.add_flag("--quiet", quiet_, "No progress on stderr");
  }

  void declare_files(OutputSet& files) override {
    files.add_inputs({options_.contour_path, options_.scan_path, options_.trajectory_path, options_.surface_path,
                      options_.truth_path});
    files.add_outputs(
        {options_.out_trajectory_path, options_.out_rows_path, options_.cad.save_mesh_path, report_path_});
  }

  int run() override {
    SicpCompensationOptions& o = options_.compensation;
    set_sicp_choices(model_, fit_, normals_, &o);
    o.sicp.joint_refinement = !no_joint_;
    options_.progress = stderr_progress(quiet_);
    options_.cad.progress = options_.progress;
    options_.keep_geometry = !report_path_.empty();
    const SicpJobResult r = run_sicp(options_);
    warn_all(r.warnings);
    if (json_) {
      print_json(sicp_json(r));
    } else {
      print_cad_text(r.cad_inputs);
      print_text(r);
    }
    if (!report_path_.empty()) {
      html::Page page = sicp_report(options_, r);
      page.date = report_date();
      write_report(report_path_, page);
    }
    if (!r.compensation.trusted) {
      std::fprintf(stderr, "conform: the compensated path cannot be trusted: %s; no trajectory written\n",
                   r.compensation.check.reason.c_str());
      return 1;
    }
    return 0;
  }

 private:
  static void print_text(const SicpJobResult& r) {
    const SicpCompensationResult& c = r.compensation;
    const SicpResult& g = c.registration;
    std::printf("contour      %zu points, %.3f mm, %s; %zu corners\n", r.contour_points, r.contour_length_mm,
                r.contour_source.c_str(), g.segmentation.corners.size());
    std::printf("scan         %zu points, %zu after thinning\n", r.scan_points, g.scan_points_used);
    std::printf("rigid        rms %.4f mm, %s after %d iterations\n", g.coarse.rms_mm,
                g.coarse.converged ? "converged" : "not converged", g.coarse.iterations);
    if (c.model == SicpModel::kSicp) {
      std::size_t converged = 0;
      for (const SicpSegmentFit& f : g.segments) converged += f.converged ? 1 : 0;
      std::printf("segments     %zu (%zu converged), rms %.4f mm\n", g.segments.size(), converged, g.rms_mm);
      std::printf("joint        %s; overlap disagreement %.4f -> %.4f mm\n", g.joint.termination.c_str(),
                  g.joint.max_disagreement_before_mm, g.joint.max_disagreement_after_mm);
    }
    if (c.model == SicpModel::kProjection) {
      std::printf("projection   %s, %zu samples, rms %.4f mm\n", to_string(c.projection.fit), c.projection.samples,
                  c.projection.rms_mm);
    }
    std::printf("model        %s: %s\n", to_string(c.model), c.converged ? "converged" : c.termination.c_str());
    std::printf("trajectory   %zu rows, %zu tool normals from the scan\n", r.trajectory_rows, c.normals_from_scan);
    if (r.error) {
      const TrajectoryError& e = *r.error;
      std::printf("vs truth     off the true path: mean %.4f mm, max %.4f mm\n", e.path_mean_mm, e.path_max_mm);
      std::printf(
          "             row by row: mean %.4f mm, max %.4f mm (row %zu); tool normals mean %.3f deg, max %.3f deg\n",
          e.mean_mm, e.max_mm, e.worst_row + 1, e.normal_mean_deg, e.normal_max_deg);
      std::printf(
          "smoothness   largest row-to-row change of the correction %.4f mm (truth %.4f mm), of the tool "
          "normal %.3f deg (truth %.3f deg)\n",
          e.max_step_mm, e.truth_step_mm, e.normal_step_max_deg, e.truth_normal_step_max_deg);
    }
    const SicpCheck& k = c.check;
    std::printf(
        "checks       noise %.4f mm; %zu blind, %zu outlier segments; %zu rows without edge scan (%zu bridged, "
        "longest stretch %.1f mm); %zu of %zu rows untrusted (lowest confidence %.2f): %s\n",
        k.noise_mm, k.blind_segments.size(), k.outlier_segments.size(), k.unmeasured_rows, k.bridged_rows,
        k.longest_gap_mm, k.untrusted_rows, k.rows.size(), k.min_confidence, c.trusted ? "trusted" : k.reason.c_str());
    if (!r.out_trajectory_path.empty()) std::printf("written      %s\n", r.out_trajectory_path.c_str());
    if (!r.out_rows_path.empty()) std::printf("written      %s\n", r.out_rows_path.c_str());
  }

  SicpJobOptions options_;
  std::string report_path_;
  std::string model_ = "sicp";
  std::string fit_ = "parabola";
  std::string normals_ = options_.compensation.normals.from_scan ? "scan" : "rotate";
  bool no_joint_ = false;
  bool json_ = false;
  bool quiet_ = false;
};

}  // namespace

CONFORM_COMMAND(SicpCommand, "sicp", "Deburring on a deformed part: Subdivision-ICP trajectory compensation")

}  // namespace conform::app
