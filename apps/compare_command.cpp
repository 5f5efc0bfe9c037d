// `conform compare`: the deviation of a scan from its reference (pipelines/compare/compare.h): statistics as text or JSON,
// optionally the deviation map (.ply) and the histogram (.png).

#include <cstdio>
#include <filesystem>
#include <string>

#include "cad_options.h"
#include "command.h"
#include "input_units.h"
#include "conform/core/units.h"
#include "conform/pipelines/compare/compare.h"
#include "conform/pipelines/compare/compare_json.h"
#include "conform/pipelines/compare/compare_report.h"
#include "conform/pipelines/common/deviation_colours.h"
#include "conform/pipelines/common/deviation_histogram.h"
#include "report_option.h"
#include "terminal.h"

namespace conform::app {
namespace {

std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

class CompareCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.description(
        "Deviation of a scan from its reference: signed distance to the reference surface (+ outside), statistics, "
        "tolerance shares, colour map, histogram");
    c.add_option("--scan", options_.scan_path, "Scan, cloud or mesh (.ply .stl .obj .pcd .xyz .txt .asc .csv)")
        ->required();
    c.add_option("--reference", options_.reference_path,
                 "Reference: a mesh (CAD as .stl/.ply/.obj: signed deviations) or a cloud (unsigned)")
        ->required();
    c.add_option("--transform", options_.transform_path,
                 "T_ref_scan, 4x4 row-major text (e.g. from `conform align --out-transform`), applied to the scan; "
                 "default: the scan is already in the reference frame");
    tolerance_ = c.add_option("--tolerance", tolerance_mm_,
                              "Tolerance band +-t, mm (> 0): in/above/below shares and the map's green band; "
                              "default none");
    c.add_option("--out-deviation", options_.out_deviation_path,
                 "Write the scan in the reference frame as .ply with per-vertex deviation_mm and colours "
                 "(blue below, green within tolerance, red above)");
    c.add_option("--out-histogram", options_.out_histogram_path,
                 "Write a histogram of the deviations as .png, the tolerance band marked");
    c.add_flag("--flat-facets", options_.flat_facets,
               "Measure to the reference mesh's flat triangles as they are, not to the smooth surface its vertices "
               "and normals describe (Phong; creases over 30 deg stay sharp), which removes the facets' chord error "
               "on curved surfaces");
    add_unit_options(c, units_,
                     "Units of the input files (mm, cm, m, in; the transform's translation is in the reference's); "
                     "results are in mm");
    add_report_option(c, report_path_);
    add_cad_options(c, options_.cad);
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override {
    files.add_inputs({options_.scan_path, options_.reference_path, options_.transform_path});
    files.add_outputs(
        {options_.out_deviation_path, options_.out_histogram_path, options_.cad.save_mesh_path, report_path_});
  }

  int run() override {
    options_.scan_mm_per_unit = millimetres_per_unit(units_.of_scan());
    options_.reference_mm_per_unit = millimetres_per_unit(units_.of_reference());
    if (*tolerance_) options_.tolerance_mm = tolerance_mm_;
    options_.colour = deviation_colour;
    const std::string title =
        "Deviation of " + file_name(options_.scan_path) + " from " + file_name(options_.reference_path);
    options_.histogram = [title](const std::vector<double>& d, const DeviationStatistics& s) {
      return deviation_histogram_png(d, s, title);
    };
    options_.progress = stderr_progress(false);
    options_.cad.progress = options_.progress;
    options_.keep_geometry = !report_path_.empty();
    const CompareResult result = run_compare(options_);
    warn_all(result.warnings);
    if (!result.deviation.note.empty()) warn(result.deviation.note);
    const nlohmann::json json = compare_json(options_, result, units_.of_scan(), units_.of_reference());
    if (!report_path_.empty()) write_report(report_path_, compare_report(options_, result, json, report_date()));
    if (json_) {
      print_json(json);
    } else {
      print_cad_text(result.cad_inputs);
      print_text(result);
      if (!report_path_.empty()) std::printf("wrote        %s\n", report_path_.c_str());
    }
    if (result.statistics.count == 0) {
      warn("no scan point was matched to the reference");
      return 1;
    }
    return 0;
  }

 private:
  void print_text(const CompareResult& r) const {
    const DeviationStatistics& s = r.statistics;
    std::printf("scan         %s (%zu points)\n", options_.scan_path.c_str(), r.scan_points);
    if (r.reference_faces > 0) {
      std::printf("reference    %s (%zu faces): signed distance to its surface, + outside%s\n",
                  options_.reference_path.c_str(), r.reference_faces,
                  options_.flat_facets ? " (flat facets)" : "");
    } else {
      std::printf("reference    %s (%zu points, no faces): unsigned distance to the nearest point\n",
                  options_.reference_path.c_str(), r.reference_points);
    }
    std::printf("transform    %s\n", options_.transform_path.empty() ? "none" : options_.transform_path.c_str());
    std::printf("matched      %zu of %zu points\n", r.deviation.matched, r.scan_points);
    std::printf("deviation mm mean %.4f  std %.4f  RMS %.4f  min %.4f  max %.4f\n", s.mean_mm, s.std_mm, s.rms_mm,
                s.min_mm, s.max_mm);
    std::printf("percentiles  p5 %.4f  p50 %.4f  p95 %.4f  p99 %.4f  p95 of |d| %.4f mm\n", s.p5_mm, s.p50_mm, s.p95_mm,
                s.p99_mm, s.p95_abs_mm);
    if (s.tolerance_mm) {
      std::printf("tolerance    +-%g mm: %.2f %% inside, %.2f %% above, %.2f %% below: %s\n", *s.tolerance_mm,
                  s.in_tolerance_pct, s.above_pct, s.below_pct,
                  s.within_tolerance() ? "within tolerance" : "OUT OF TOLERANCE");
    }
    if (!r.out_deviation_path.empty()) std::printf("wrote        %s\n", r.out_deviation_path.c_str());
    if (!r.out_histogram_path.empty()) std::printf("wrote        %s\n", r.out_histogram_path.c_str());
  }

  CompareOptions options_;
  CLI::Option* tolerance_ = nullptr;
  double tolerance_mm_ = 0.0;
  InputUnits units_;
  std::string report_path_;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(CompareCommand, "compare",
                "Deviation of a scan from its reference: statistics, tolerance shares, colour map, histogram")

}  // namespace conform::app
