// `conform align`: registers a scan to its reference (pipelines/align/align.h) and reports T_ref_scan, convergence, the fit
// figures, the pose's predicted standard deviations, what the scan does not constrain and whether to trust the pose.
// Exit code 1 when ICP did not converge or the pose is not to be trusted (verdict "no").

#include <cmath>
#include <cstdio>
#include <string>

#include "cad_options.h"
#include "command.h"
#include "input_units.h"
#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/core/units.h"
#include "conform/pipelines/align/align.h"
#include "conform/pipelines/align/align_json.h"
#include "conform/pipelines/align/align_report.h"
#include "report_option.h"
#include "terminal.h"

namespace conform::app {
namespace {


// A default as --help shows it: three significant digits.
std::string shown(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

std::string vector_text(const Eigen::Vector3d& v, int decimals) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "(%.*f, %.*f, %.*f)", decimals, v.x(), decimals, v.y(), decimals, v.z());
  return buffer;
}

// "translation along (0, 0, 1)", "rotation about (0, 0, 1) through (0, 0, 0) mm".
std::string describe(const DegenerateDirection& d) {
  if (d.kind == MotionKind::kTranslation) return "translation along " + vector_text(d.direction, 4);
  return "rotation about " + vector_text(d.direction, 4) + " through " + vector_text(d.point, 3) + " mm";
}

// Why ICP stopped, in words a user can act on.
std::string failure_message(const AlignResult& r) {
  const IcpResult& icp = r.icp;
  char distance[64];
  std::snprintf(distance, sizeof distance, "%g mm", r.max_distance_mm);
  switch (icp.termination) {
    case IcpTermination::kTooFewCorrespondences:
      return "registration did not converge: too few scan points (" + std::to_string(icp.inliers) + " of " +
             std::to_string(r.scan_points_used) + ") lie within " + distance +
             " of the reference. Do scan and reference overlap? Place the scan coarsely (--init pca, --init fpfh, "
             "--init pairs:FILE) or raise --max-distance";
    case IcpTermination::kInsufficientOverlap: {
      char share[32];
      std::snprintf(share, sizeof share, "%.1f%%", 100.0 * icp.inlier_fraction);
      return std::string("registration did not converge: it settled on ") + share +
             " of the scan only, too little to trust. Do scan and reference overlap? Try --init pca or fpfh";
    }
    case IcpTermination::kMaxIterations:
      return "registration did not converge within " + std::to_string(icp.iterations) + " iterations (last step " +
             std::to_string(icp.last_rotation_rad * kDegPerRad) + " deg, " + std::to_string(icp.last_translation_mm) +
             " mm). Raise --max-iterations, or start closer (--init)";
    case IcpTermination::kConverged:
      return "the pose is not to be trusted: " + r.verdict.summary.substr(r.verdict.summary.find(": ") + 2) +
             ". Check the start (--init fpfh, pca or pairs:FILE), the units and that scan and reference are the same "
             "part";
    default:
      return std::string("registration did not converge: ") + to_string(icp.termination);
  }
}

class AlignCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.description("Register a scan to its reference: rigid T_ref_scan (ICP after an optional coarse placement)");
    c.add_option("--scan", options_.scan_path, "Scan, cloud or mesh (.ply .stl .obj .pcd .xyz .txt .asc .csv)")
        ->required();
    c.add_option("--reference", options_.reference_path,
                 "Reference: CAD mesh or cloud, same formats; or CAD (.step .stp .iges .igs)")
        ->required();
    c.add_option("--method", method_,
                 "point-to-point, point-to-plane, point-to-surface (closest point on the reference's triangles) or "
                 "plane-to-plane (generalized ICP; also 'gicp'); default " +
                     std::string(to_string(default_align_method(true))) + " for a mesh reference, " +
                     to_string(default_align_method(false)) + " for a cloud")
        ->check(CLI::IsMember({"point-to-point", "point-to-plane", "point-to-surface", "plane-to-plane", "gicp"}));
    c.add_option("--init", init_,
                 "Coarse placement: none (the scan is roughly in place), pca (principal axes, all sign choices "
                 "tried), fpfh (FPFH features + RANSAC; partial overlap) or pairs:FILE (>= 3 point pairs, one per "
                 "line: scan x y z reference x y z)");
    c.add_option("--max-distance", options_.max_distance_mm,
                 "Pairs farther apart are ignored, mm; default " +
                     std::to_string(std::lround(100.0 * kAlignAutoDistanceShare)) + "%" +
                     " of the reference's bounding-box diagonal");
    c.add_option("--overlap", options_.overlap,
                 "Share of the scan that overlaps the reference, (0, 1]; the rest is trimmed; 0: estimated in every "
                 "step from the pairs' distances (fractional ICP)");
    c.add_option("--max-iterations", options_.max_iterations, "ICP iterations at most");
    c.add_option("--pose-tolerance-mm", options_.pose_tolerance_mm,
                 "The accuracy asked of the pose, mm: the largest predicted std of any scan point's displacement "
                 "(from the residuals, the surface's constraint and, against a cloud, the fit's bias and the normals' "
                 "model); a pose from "
                 "--init pca/fpfh that misses it is refused (exit 1), one from a start you gave is 'check'; 0: a sixth "
                 "of --tolerance when given, else " + shown(kAlignPoseNoiseShare) + " times the noise of the scan or of "
                     "the fit, whichever is larger (at least " + shown(kAlignFinestNoiseMm) + " mm)");
    c.add_option("--tolerance", options_.tolerance_mm,
                 "The inspection tolerance +-mm the pose serves (as compare --tolerance); sets the default "
                 "--pose-tolerance-mm; 0: not stated");
    c.add_option("--free-tolerance-mm", options_.free_tolerance_mm,
                 "A weak motion whose predicted std exceeds this along an axis, mm, is held at the start when the "
                 "coarse stage found the fit unchanged along it (a tube's axis)");
    c.add_option("--free-tolerance-deg", options_.free_tolerance_deg,
                 "The same about an axis, deg");
    c.add_option("--max-noise-ratio", options_.max_noise_ratio,
                 "Residuals more than this many times the scan's own noise: the pose is not trusted (exit 1); 0: "
                 "no check");
    add_unit_options(c, units_,
                     "Units of both input files and the pairs file's columns (mm, cm, m, in); outputs are in mm");
    c.add_option("--out-transform", options_.out_transform_path,
                 "Write T_ref_scan (4x4 row-major text, mm) unless the pose is not to be trusted");
    c.add_option("--out-aligned", options_.out_aligned_path,
                 "Write the scan moved into the reference frame (mm), mesh or cloud as read, unless the pose is not "
                 "to be trusted");
    add_report_option(c, report_path_);
    add_cad_options(c, options_.cad);
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override {
    files.add_inputs({options_.scan_path, options_.reference_path});
    if (init_.rfind("pairs:", 0) == 0) files.add_input(init_.substr(6));
    files.add_outputs(
        {options_.out_transform_path, options_.out_aligned_path, options_.cad.save_mesh_path, report_path_});
  }

  int run() override {
    options_.scan_mm_per_unit = millimetres_per_unit(units_.of_scan());
    options_.reference_mm_per_unit = millimetres_per_unit(units_.of_reference());
    set_align_method(method_, &options_);
    set_align_init(init_, &options_);
    options_.progress = stderr_progress(false);
    options_.cad.progress = options_.progress;
    options_.keep_geometry = !report_path_.empty();
    const AlignResult result = run_align(options_);
    warn_all(result.warnings);
    const nlohmann::json json = align_json(result);
    if (!report_path_.empty()) write_report(report_path_, align_report(options_, result, json, report_date()));
    if (json_) {
      print_json(json);
    } else {
      print_cad_text(result.cad_inputs);
      print_text(result);
    }
    if (result.icp.degeneracy.degenerate()) {
      warn("the scan does not constrain every degree of freedom; these motions were held at the start pose: " +
           degenerate_list(result.icp.degeneracy));
    }
    if (result.verdict.trust == AlignTrust::kNo) {
      std::fprintf(stderr, "conform: %s\n", failure_message(result).c_str());
      return 1;
    }
    if (result.verdict.trust == AlignTrust::kCheck) warn(result.verdict.summary);
    return 0;
  }

 private:
  static std::string degenerate_list(const DegeneracyReport& report) {
    std::string out;
    for (const DegenerateDirection& d : report.directions) out += (out.empty() ? "" : "; ") + describe(d);
    return out;
  }

  static void print_text(const AlignResult& r) {
    const IcpResult& icp = r.icp;
    std::printf("scan          %zu points, %zu used\n", r.scan_points, r.scan_points_used);
    std::printf("reference     %zu points, %zu faces\n", r.reference_points, r.reference_faces);
    std::printf("method        %s, max distance %.4g mm, start %s (init %s", to_string(r.method), r.max_distance_mm,
                r.start.c_str(), to_string(r.init));
    if (!r.coarse.ranking.starts.empty()) {
      std::printf(", best of %zu starts%s", r.coarse.ranking.starts.size(),
                  r.coarse.ranking.ambiguous ? ", ambiguous" : "");
    }
    std::printf(")\n");
    for (std::size_t i = 0; i < r.pairs.residuals_mm.size(); ++i) {
      std::printf("pair %-8zu residual %.4f mm\n", i + 1, r.pairs.residuals_mm[i]);
    }
    std::printf("converged     %s (%s after %d iterations)\n", icp.converged ? "yes" : "no", to_string(icp.termination),
                icp.iterations);
    std::printf("rms mm        %.6f\n", icp.rms_mm);
    std::printf("inliers       %.2f %%\n", 100.0 * icp.inlier_fraction);
    for (int row = 0; row < 4; ++row) {
      std::printf("%s %14.9f %14.9f %14.9f %16.9f\n", row == 0 ? "T_ref_scan   " : "             ",
                  icp.T_ref_scan(row, 0), icp.T_ref_scan(row, 1), icp.T_ref_scan(row, 2), icp.T_ref_scan(row, 3));
    }
    const Eigen::VectorXd& e = icp.degeneracy.eigenvalues;
    std::printf("eigenvalues  ");
    for (Eigen::Index i = 0; i < e.size(); ++i) std::printf(" %.3g", e(i));
    std::printf("  (smallest/largest %.3g)\n", icp.degeneracy.relative_smallest());
    if (icp.degeneracy.directions.empty()) std::printf("degenerate    none: all degrees of freedom constrained\n");
    for (const DegenerateDirection& d : icp.degeneracy.directions) {
      const bool t = d.kind == MotionKind::kTranslation;
      std::printf("degenerate    %s (predicted std %.3g %s, relative eigenvalue %.2g)\n", describe(d).c_str(),
                  t ? d.std_mm : d.std_rad * kDegPerRad, t ? "mm" : "deg", d.relative_eigenvalue);
    }
    const Vector6d& s = icp.degeneracy.std;
    std::printf(
        "pose std      rx %.2g ry %.2g rz %.2g deg, tx %.2g ty %.2g tz %.2g mm (free above %.3g mm, %.3g deg)\n",
        s(0) * kDegPerRad, s(1) * kDegPerRad, s(2) * kDegPerRad, s(3), s(4), s(5), icp.degeneracy.tolerance_mm,
        icp.degeneracy.tolerance_rad * kDegPerRad);
    const AlignVerdict& v = r.verdict;
    std::printf("noise mm      fit %.4g, scan %.4g", v.fit_noise_mm, v.scan_noise_mm);
    if (v.reference_noise_mm > 0.0) std::printf(", reference %.4g", v.reference_noise_mm);
    std::printf(" (ratio %.2f)\n", v.noise_ratio);
    if (!r.transform_path.empty()) std::printf("transform     %s\n", r.transform_path.c_str());
    if (!r.aligned_path.empty()) std::printf("aligned       %s\n", r.aligned_path.c_str());
    std::printf("verdict       %s\n", v.summary.c_str());
  }

  AlignOptions options_;
  std::string method_;
  std::string init_ = "none";
  InputUnits units_;
  std::string report_path_;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(AlignCommand, "align", "Register a scan to its reference (ICP, coarse placement, degeneracy report)")

}  // namespace conform::app
