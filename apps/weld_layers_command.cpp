// `conform weld-layers`: the boundary of the eroded area and parallel weld paths, layer by layer, to rebuild an
// eroded surface (Simas, Dias & Guenther; pipelines/weld_layers.h).

#include <cstdio>
#include <string>

#include "command.h"
#include "conform/core/error.h"
#include "conform/pipelines/weld_layers.h"
#include "terminal.h"

namespace conform::app {
namespace {

class WeldLayersCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.add_option("--eroded", o_.eroded_path, "Eroded grid CSV row,col,x_mm,y_mm,z_mm (full rectangular grid); required")
        ->required();
    CLI::Option* reference = c.add_option("--reference", o_.reference_path, "Reference (original) grid CSV, same columns");
    CLI::Option* border = c.add_flag("--reference-from-border", from_border_,
                                     "No reference file: rebuild it as the Coons patch of the eroded grid's border "
                                     "(the damage must stay clear of the border)");
    reference->excludes(border);
    c.add_option("--bead-spacing", o_.weld.bead_spacing_mm, "Bead spacing dc within a layer, mm; required")->required();
    c.add_option("--layer-height", o_.weld.layer_height_mm, "Layer height cd, mm; required")->required();
    c.add_option("--chord-error", o_.weld.chord_error_mm, "Max chord error delta of a path step, mm; required")
        ->required();
    c.add_option("--torch-distance", o_.weld.torch_distance_mm, "Torch-to-surface distance w (Eq. 5), mm");
    c.add_option("--layers", o_.weld.layers, "Number of layers; default 0 = ceil(max depth / layer height)");
    c.add_option("--depth-threshold", o_.weld.depth_threshold_mm,
                 "Depth below the reference where the damage starts, mm; default 6 x the estimated noise (>= 0.01); "
                 "0 = plain intersection");
    c.add_option("--out", o_.out_path, "CSV to write: layer,path,i,x_mm,y_mm,z_mm,nx,ny,nz");
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override {
    files.add_inputs({o_.eroded_path, o_.reference_path});
    files.add_output(o_.out_path);
  }

  int run() override {
    if (o_.reference_path.empty() && !from_border_) {
      throw Error("weld-layers: give --reference FILE or --reference-from-border");
    }
    const WeldLayersJobResult job = run_weld_layers(o_);
    const WeldLayerResult& w = job.weld;
    if (json_) {
      print_json(to_json(job));
    } else {
      print_text(job);
    }
    if (!w.ok) {
      warn("weld-layers: " + w.termination + "; no file written");
      return 1;
    }
    return 0;
  }

 private:
  nlohmann::json to_json(const WeldLayersJobResult& job) const {
    const WeldLayerResult& w = job.weld;
    nlohmann::json rims = nlohmann::json::array();
    for (const IntersectionCurve& c : w.rims) rims.push_back({{"points", c.points.size()}, {"length_mm", c.length_mm()}});
    return {{"ok", w.ok},
            {"termination", w.termination},
            {"layers", w.layers},
            {"paths", w.paths.size()},
            {"half_step_paths", w.half_step_paths},
            {"total_length_mm", w.total_length_mm},
            {"spacing_error_pct_max", w.spacing_error_pct_max},
            {"chord_error_mm_max", w.chord_error_mm_max},
            {"coverage_pct_min", w.coverage_pct_min},
            {"coverage_pct_by_layer", w.coverage_pct},
            {"noise_mm", w.noise_mm},
            {"depth_threshold_mm", w.depth_threshold_mm},
            {"depth_threshold_estimated", w.threshold_estimated},
            {"max_depth_mm", w.max_depth_mm},
            {"rims", rims},
            {"open_curves", w.open_curves},
            {"loops_removed", w.loops_removed},
            {"newton_offsets", w.newton_offsets},
            {"bead_spacing_mm", o_.weld.bead_spacing_mm},
            {"layer_height_mm", o_.weld.layer_height_mm},
            {"chord_error_mm", o_.weld.chord_error_mm},
            {"torch_distance_mm", o_.weld.torch_distance_mm},
            {"reference", from_border_ ? "coons patch of the eroded border" : o_.reference_path},
            {"out", job.out_path.empty() ? nlohmann::json(nullptr) : nlohmann::json(job.out_path)}};
  }

  void print_text(const WeldLayersJobResult& job) const {
    const WeldLayerResult& w = job.weld;
    std::printf("grids         eroded %d x %d, reference %d x %d\n", job.eroded_rows, job.eroded_cols,
                job.reference_rows, job.reference_cols);
    std::printf("depth         noise %.4f mm, threshold %.4f mm (%s), max depth %.4f mm\n", w.noise_mm,
                w.depth_threshold_mm, w.threshold_estimated ? "6 x noise" : "given", w.max_depth_mm);
    std::printf("rims          %zu closed", w.rims.size());
    for (std::size_t k = 0; k < w.rims.size() && k < 6; ++k) std::printf(" (%.3f mm)", w.rims[k].length_mm());
    if (w.rims.size() > 6) std::printf(" ...");
    std::printf(", %zu open\n", w.open_curves);
    if (!w.ok) return;
    std::printf("layers        %d, paths %zu (%zu half-step paths before clipping)\n", w.layers, w.paths.size(),
                w.half_step_paths);
    std::printf("length        %.3f mm in total\n", w.total_length_mm);
    std::printf("spacing       max error %.4f %%\n", w.spacing_error_pct_max);
    std::printf("chord error   max %.6f mm\n", w.chord_error_mm_max);
    std::printf("coverage %%    ");
    for (double pct : w.coverage_pct) std::printf(" %.2f", pct);
    std::printf("  (by layer: share of its region within 0.55 bead spacing of a path)\n");
    std::printf("loops removed %zu, Newton offsets %zu\n", w.loops_removed, w.newton_offsets);
    std::printf("out           %s\n", job.out_path.empty() ? "(none)" : job.out_path.c_str());
  }

  WeldLayersJobOptions o_;
  bool from_border_ = false;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(WeldLayersCommand, "weld-layers",
                "Boundary of eroded craters and parallel weld paths layer by layer (Simas, Dias & Guenther)")

}  // namespace conform::app
