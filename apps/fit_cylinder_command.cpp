// `conform fit-cylinder --input FILE`: the axis, radius, inliers and residual figures of a scanned tube
// (pipelines/fit_cylinder/fit_cylinder.h). Exit 1 when the data do not define a cylinder (a plane, a sphere, too few inliers).

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "cad_options.h"
#include "command.h"
#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/pipelines/fit_cylinder/fit_cylinder.h"
#include "conform/pipelines/fit_cylinder/fit_cylinder_json.h"
#include "conform/pipelines/fit_cylinder/fit_cylinder_report.h"
#include "report_option.h"
#include "terminal.h"

namespace conform::app {
namespace {

class FitCylinderCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.description("Fit a cylinder to a tube scan: RANSAC on points and normals, then geometric least squares");
    c.add_option("--input", options_.input_path,
                 "Scan to fit, cloud or mesh (.ply .stl .obj .pcd .xyz .txt .asc .csv), or CAD; required")
        ->required();
    c.add_option("--threshold", options_.fit.threshold_mm,
                 "Inlier distance to the surface, mm; default 0 = automatic (" +
                     CLI::detail::to_string(options_.fit.inlier_sigmas) + " noise sigmas, estimated)");
    c.add_option("--min-radius", options_.fit.min_radius_mm, "Smallest radius accepted, mm");
    max_radius_ = c.add_option("--max-radius", max_radius_mm_, "Largest radius accepted, mm; 0: none");
    c.add_option("--axis", axis_, "Expected axis direction x y z (any length, either sign)")->expected(3);
    c.add_option("--axis-tolerance-deg", axis_tolerance_deg_, "Largest angle of the axis from --axis, deg");
    c.add_option("--normals-k", options_.fit.normal_neighbors, "Neighbours of the PCA normals when the file has none");
    c.add_option("--seed", options_.fit.seed, "Seed of the RANSAC draws");
    c.add_option("--max-shape-ambiguity", options_.fit.max_shape_ambiguity_mm,
                 "Warn when an ovality the residuals cannot show (a partial arc) could move the axis or the radius by "
                 "more than this, mm")
        ->check(CLI::NonNegativeNumber);
    c.add_option("--out", options_.out_path, "CSV of every point: i,x_mm,y_mm,z_mm,distance_mm,inlier");
    add_report_option(c, report_path_);
    c.add_option("--points", points_,
                 "Points to fit: auto (a CAD input's surface, any other input's vertices), vertices, or surface "
                 "(samples of a mesh's smooth surface: for a coarse mesh whose vertices lie on its rims only)")
        ->check(CLI::IsMember({"auto", "vertices", "surface"}));
    c.add_option("--surface-samples", options_.surface_samples,
                 "Surface points: how many, spread by area over the mesh's smooth surface")
        ->check(CLI::PositiveNumber);
    add_cad_options(c, options_.cad);
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
    c.add_flag("--quiet", quiet_, "No progress on stderr");
  }

  void declare_files(OutputSet& files) override {
    files.add_input(options_.input_path);
    files.add_outputs({options_.out_path, options_.cad.save_mesh_path, report_path_});
  }

  int run() override {
    if (max_radius_->count() > 0) options_.fit.max_radius_mm = max_radius_mm_;
    options_.points = points_ == "vertices" ? CylinderPoints::kVertices
                      : points_ == "surface" ? CylinderPoints::kSurface
                                             : CylinderPoints::kAuto;
    if (!axis_.empty()) options_.fit.axis_prior = Eigen::Vector3d(axis_[0], axis_[1], axis_[2]);
    options_.fit.axis_prior_tolerance_rad = radians(axis_tolerance_deg_);
    if (!axis_.empty() && !(options_.fit.axis_prior.norm() > 0.0)) throw Error("--axis: the direction is zero");
    options_.fit.progress = stderr_progress(quiet_ || json_);
    options_.cad.progress = options_.fit.progress;
    options_.keep_geometry = !report_path_.empty();
    const FitCylinderJobResult result = run_fit_cylinder(options_);
    warn_all(result.warnings);
    const nlohmann::json json = fit_cylinder_json(result);
    if (!report_path_.empty()) write_report(report_path_, fit_cylinder_report(options_, result, json, report_date()));
    if (json_) {
      print_json(json);
    } else {
      print_cad_text(result.cad_inputs);
      print_text(result);
    }
    if (!result.fit.ok) {
      warn("fit-cylinder: " + result.input_path + ": " + result.fit.termination +
           (result.input_faces > 0 && !result.surface_points
                ? " (a coarse mesh, e.g. exported from CAD, may have vertices on its rims only: try --points surface)"
                : ""));
      return 1;
    }
    return 0;
  }

 private:
  static void print_text(const FitCylinderJobResult& job) {
    const CylinderFitResult& f = job.fit;
    const Eigen::Vector3d& c = f.cylinder.axis_point;
    const Eigen::Vector3d& a = f.cylinder.axis_direction;
    std::printf("input         %s (%zu %s, normals: %s)\n", job.input_path.c_str(), job.points,
                job.surface_points ? "surface samples" : "points", to_string(job.normals));
    std::printf("result        %s\n", f.ok ? "cylinder" : f.termination.c_str());
    if (f.refine_rounds == 0) return;  // no model to describe: RANSAC found none
    std::printf("radius mm     %.4f  (std %.4f)\n", f.cylinder.radius_mm, f.radius_std_mm);
    std::printf("axis point mm %.4f %.4f %.4f  (std %.4f)\n", c.x(), c.y(), c.z(), f.axis_point_std_mm);
    std::printf("axis dir      %.8f %.8f %.8f  (std %.5f deg)\n", a.x(), a.y(), a.z(), degrees(f.axis_angle_std_rad));
    std::printf("inliers       %zu (%.2f %%) within %.4f mm; rms %.4f mm, noise sigma %.4f mm\n", f.inliers.size(),
                100.0 * f.inlier_fraction, f.threshold_mm, f.rms_mm, f.noise_sigma_mm);
    std::printf("arc deg       %.2f  (%s surface)\n", degrees(f.arc_rad), to_string(f.side));
    std::printf("shape mm      %.4f systematic deviation from the circle", f.shape_deviation_mm);
    if (f.shape_axis_ambiguity_mm > 0.0 || f.shape_radius_ambiguity_mm > 0.0) {
      std::printf("; the ovality these residuals allow (%.4f) moves the axis up to %.4f, the radius up to %.4f",
                  f.hidden_ovality_mm, f.shape_axis_ambiguity_mm, f.shape_radius_ambiguity_mm);
    }
    std::printf("\n");
    std::printf("solver        %d RANSAC draws, %d rounds, %d LM iterations, %s\n", f.ransac_iterations,
                f.refine_rounds, f.solver_iterations, f.converged ? "converged" : "not converged");
    std::printf("out           %s\n", job.out_path.empty() ? "(none)" : job.out_path.c_str());
  }

  FitCylinderJobOptions options_;
  double max_radius_mm_ = 0.0;
  CLI::Option* max_radius_ = nullptr;
  std::vector<double> axis_;
  double axis_tolerance_deg_ = 10.0;
  std::string report_path_;
  std::string points_ = "auto";
  bool json_ = false;
  bool quiet_ = false;
};

}  // namespace

CONFORM_COMMAND(FitCylinderCommand, "fit-cylinder",
                "Fit a cylinder (axis, radius, inliers, covariance) to a tube scan: RANSAC + Ceres least squares")

}  // namespace conform::app
