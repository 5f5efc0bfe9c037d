// `conform profile`: compensate the cutting and marking coordinates of a deformed ship profile from its measured
// edge (Chen et al., LNG profiles; beyond the paper: spline edge model chosen by residual, local web direction from a
// second edge, per-feature comparison with the cubic model).

#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "conform/core/error.h"
#include "conform/pipelines/profile/profile.h"
#include "conform/pipelines/profile/profile_json.h"
#include "conform/pipelines/profile/profile_report.h"
#include "number_list.h"
#include "report_option.h"
#include "terminal.h"

namespace conform::app {
namespace {

// "0,0,1" -> a finite non-zero vector, or conform::Error naming the flag.
Eigen::Vector3d parse_web_normal(const std::string& text) {
  const std::vector<double> values = parse_numbers(text, 3, "--web-normal", "x,y,z");
  const Eigen::Vector3d z(values[0], values[1], values[2]);
  if (!(z.norm() > 0.0)) throw Error("--web-normal " + text + ": the web normal must not be zero");
  return z;
}

class ProfileCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.add_option("--edge", request_.edge_path,
                 "Measured edge points, CSV x_mm,y_mm,z_mm in measuring order (origin first); required")
        ->required();
    c.add_option("--features", request_.features_path,
                 "Designed features, .csv (id,type,tx_mm,ty_mm,radius_mm) or .json (docs/profile.md); required")
        ->required();
    c.add_option("--model", request_.model, "Edge model: auto (the lower BIC of cubic and spline), cubic, spline")
        ->check(CLI::IsMember({"auto", "cubic", "spline"}));
    web_ = c.add_option("--web-normal", web_normal_,
                                    "Web normal Z, x,y,z (any length; its sign picks the side Tx goes to), machine "
                                    "+z as in the paper");
    CLI::Option* plane = c.add_flag("--web-plane", request_.web_plane,
                                    "Z = the normal of the edge points' plane instead (warned when tilted from +z)");
    CLI::Option* second = c.add_option("--second-edge", request_.second_edge_path,
                                       "The profile's other edge (+Tx side), CSV x_mm,y_mm,z_mm: local web direction "
                                       "for twist");
    web_->excludes(second);
    web_->excludes(plane);
    plane->excludes(second);
    c.add_option("--web-width", request_.web_width_mm,
                 "Web width, mm: features beyond Tx = width are refused (0: unknown; a second edge measures it)");
    c.add_option("--direction", request_.direction,
                 "Edge points listed from the origin (forward) or from the profile's far end (reverse)")
        ->check(CLI::IsMember({"forward", "reverse"}));
    c.add_option("--knot-spacing", request_.knot_spacing_mm, "Spline knot spacing, mm (0: max(10 steps, 250 sigma, 20 mm))");
    c.add_option("--outlier-sigma", request_.outlier_sigma,
                 "Edge points further than this many robust sigmas from the fitted edge are outliers");
    c.add_option("--chord-tolerance", request_.chord_tolerance_mm, "Largest chord error of a mapped outline, mm");
    c.add_option("--max-gap", request_.max_gap_mm, "Largest allowed distance between consecutive edge points, mm");
    c.add_option("--noise", request_.noise_mm, "Edge sensor noise sigma per coordinate, mm (0: estimate it)");
    c.add_option("--out", request_.out_path,
                 "CSV to write: id,i,tx_mm,ty_mm,x_mm,y_mm,z_mm,nx,ny,nz (web normal),dx,dy,dz (cut direction)");
    add_report_option(c, report_);
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override {
    files.add_inputs({request_.edge_path, request_.features_path, request_.second_edge_path});
    files.add_outputs({request_.out_path, report_});
  }

  int run() override {
    if (web_->count() > 0) request_.web_normal = parse_web_normal(web_normal_);
    ProfileJobOptions options = profile_job_options(request_);
    options.keep_geometry = !report_.empty();
    const ProfileJobResult result = run_profile(options);
    if (json_) {
      print_json(profile_json(options, result));
    } else {
      print_text(result);
    }
    if (!report_.empty()) {
      html::Page page = profile_report(options, result);
      page.date = report_date();
      write_report(report_, page);
    }
    for (const std::string& w : result.compensation.warnings) warn("profile: " + w);
    if (!result.compensation.ok) {
      warn("profile: " + result.compensation.termination + "; no file written");
      return 1;
    }
    return 0;
  }

 private:
  void print_text(const ProfileJobResult& job) const {
    const ProfileCompensationResult& r = job.compensation;
    const ProfileEdgeFit& e = r.edge;
    std::printf("edge          %zu points, %.3f mm long, spacing median %.3f mm, largest gap %.3f mm, noise %.4f mm\n",
                job.edge_points, e.curve.length_mm(), e.points.median_spacing_mm, e.points.max_gap_mm, e.noise_mm);
    std::printf(
        "edge points   %zu outliers rejected (%d passes), %zu duplicates dropped, %zu out of order within "
        "the noise\n",
        e.outliers, e.reweighting_passes, e.duplicates_dropped, e.points.reordered);
    std::printf("cubic fit     RMS %.4f mm  max %.4f mm\n", e.cubic_fit.rms_mm, e.cubic_fit.max_mm);
    if (e.spline_fit.fitted) {
      std::printf("spline fit    RMS %.4f mm  max %.4f mm\n", e.spline_fit.rms_mm, e.spline_fit.max_mm);
    }
    std::printf("model         %s (%s)\n", to_string(e.model), e.selection.c_str());
    if (r.local_web) {
      std::printf("web           local, from the second edge (%zu points): width %.3f .. %.3f mm\n",
                  job.second_edge_points, r.web_width_min_mm, r.web_width_max_mm);
    } else {
      std::printf("web normal    %.6f %.6f %.6f (%s, %.2f deg from +z)\n", r.web_normal.x(), r.web_normal.y(),
                  r.web_normal.z(), r.web_source.c_str(), r.web_tilt_deg);
    }
    std::printf("mapped        %zu points, arc-length residual max %.2e mm\n", r.mapped_points,
                r.arc_length_residual_max_mm);
    for (const ProfileFeatureResult& f : r.features) {
      std::printf("  %-10s %-8s %5zu pts", f.id.c_str(), to_string(f.type), f.mapped.size());
      if (f.has_centre) std::printf("  centre %.3f %.3f %.3f", f.centre.x(), f.centre.y(), f.centre.z());
      if (e.model != ProfileEdgeModel::kCubic) std::printf("  vs cubic %.3f mm", f.cubic_deviation_max_mm);
      std::printf("\n");
    }
    std::printf("out           %s\n", job.out_path.empty() ? "(none)" : job.out_path.c_str());
  }

  ProfileRequest request_;
  std::string web_normal_ = "0,0,1";
  CLI::Option* web_ = nullptr;
  std::string report_;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(
    ProfileCommand, "profile",
    "Compensate cutting/marking coordinates of a deformed ship profile from its measured edge (Chen et al.)")

}  // namespace conform::app
