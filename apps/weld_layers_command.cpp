// `conform weld-layers`: the boundary of the eroded area and parallel weld paths, layer by layer, to rebuild an
// eroded surface (Simas, Dias & Guenther; pipelines/weld_layers/weld_layers.h).

#include <cmath>
#include <cstdio>
#include <string>

#include "command.h"
#include "conform/core/error.h"
#include "conform/pipelines/weld_layers/weld_layers.h"
#include "conform/pipelines/weld_layers/weld_layers_json.h"
#include "conform/pipelines/weld_layers/weld_layers_report.h"
#include "report_option.h"
#include "terminal.h"

namespace conform::app {
namespace {

class WeldLayersCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.add_option("--eroded", o_.eroded_path, "Eroded grid CSV row,col,x_mm,y_mm,z_mm (full rectangular grid); required")
        ->required();
    CLI::Option* reference =
        c.add_option("--reference", o_.reference_path, "Reference (original) grid CSV, same columns");
    CLI::Option* border = c.add_flag("--reference-from-border", from_border_,
                                     "No reference file: rebuild it as the Coons patch of the eroded grid's border "
                                     "(the damage must stay clear of the border)");
    reference->excludes(border);
    c.add_option("--bead-spacing", o_.weld.bead_spacing_mm, "Bead spacing dc within a layer, mm; required")->required();
    c.add_option("--layer-height", o_.weld.layer_height_mm, "Layer height cd, mm; required")->required();
    c.add_option("--chord-error", o_.weld.chord_error_mm, "Max chord error delta of a path step, mm; required")
        ->required();
    c.add_option("--torch-distance", o_.weld.torch_distance_mm,
                 "Torch standoff w along the normal, mm (the beads are planned on the surface whatever it is)");
    c.add_option("--bead-width", o_.weld.bead_width_mm,
                 "Bead width on the surface for coverage and overlap, mm; 0 = the bead spacing");
    c.add_option("--max-overlap", o_.weld.max_overlap_mm,
                 "Most path length of a layer within half a bead of another of its paths, mm; beyond: exit 1");
    c.add_option("--layers", o_.weld.layers, "Number of layers; 0 = ceil((max depth - threshold) / layer height)")
        ->check(CLI::Range(0, kMaxWeldLayers));
    c.add_option("--depth-threshold", o_.weld.depth_threshold_mm,
                 "Depth below the reference where the damage starts, mm; < 0: 6 x the estimated noise (>= 0.01 mm); "
                 "0 = any depth");
    c.add_option("--outward", o_.weld.outward_side,
                 "Which side of the reference the torch is on: +1 along its r_u x r_v, -1 against; 0 = from the data")
        ->check(CLI::Range(-1, 1));
    c.add_option("--bias", bias_,
                 "Registration offset/tilt of the eroded grid against the reference: check (a significant one fails, "
                 "exit 1), remove (subtract it), keep (refill it as damage)")
        ->check(CLI::IsMember({"check", "remove", "keep"}));
    c.add_option("--min-coverage", o_.weld.min_coverage_pct,
                 "Least share of the damage within half a bead width of a layer-1 path, %; below: exit 1");
    c.add_option("--min-crater-coverage", o_.weld.min_crater_coverage_pct,
                 "Least share of any one crater (larger than a bead) covered by layer 1, %; below: exit 1 naming it");
    c.add_option("--out", o_.out_path, "CSV to write: layer,path,i,x_mm,y_mm,z_mm,nx,ny,nz");
    add_report_option(c, report_);
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override {
    files.add_inputs({o_.eroded_path, o_.reference_path});
    files.add_outputs({o_.out_path, report_});
  }

  int run() override {
    if (o_.reference_path.empty() && !from_border_) {
      throw Error("weld-layers: give --reference FILE or --reference-from-border");
    }
    o_.weld.bias = bias_ == "remove" ? BiasMode::kRemove : bias_ == "keep" ? BiasMode::kKeep : BiasMode::kCheck;
    o_.keep_geometry = !report_.empty();
    const WeldLayersJobResult job = run_weld_layers(o_);
    const WeldLayerResult& w = job.weld;
    if (json_) {
      print_json(weld_layers_json(o_, job));
    } else {
      print_text(job);
    }
    if (!report_.empty()) {
      html::Page page = weld_layers_report(o_, job);
      page.date = report_date();
      write_report(report_, page);
    }
    for (const std::string& text : w.warnings) warn("weld-layers: warning: " + text);
    if (!w.ok) {
      warn("weld-layers: " + w.termination + "; no file written");
      return 1;
    }
    return 0;
  }

 private:
  void print_text(const WeldLayersJobResult& job) const {
    const WeldLayerResult& w = job.weld;
    std::printf("grids         eroded %d x %d, reference %d x %d\n", job.eroded_rows, job.eroded_cols,
                job.reference_rows, job.reference_cols);
    const DamageMap& d = w.damage;
    std::printf("depth         noise %.4f mm, threshold %.4f mm (%s), max depth %.4f mm\n", w.noise_mm,
                w.depth_threshold_mm, w.threshold_estimated ? "6 x noise" : "given", w.max_depth_mm);
    std::printf("bias          offset %.4f mm, tilt %.4f deg, up to %.4f mm (%s%s)\n", d.bias_offset_mm,
                d.bias_tilt_deg, d.bias_span_mm, d.bias_significant ? "significant" : "within the noise",
                d.bias_removed ? ", removed" : "");
    std::printf("side          torch along %s r_u x r_v of the reference (%s)\n", d.outward_sign > 0 ? "+" : "-",
                d.side_from_data ? "from the data" : "given");
    std::printf("craters       %zu\n", d.regions.size());
    for (const DamageRegion& r : d.regions) {
      std::printf("  %-3d         %.2f mm deep at (%.1f, %.1f, %.1f), %.1f mm^2%s", r.id, r.max_depth_mm, r.deepest.x(),
                  r.deepest.y(), r.deepest.z(), r.area_mm2, r.at_border ? ", at the border" : "");
      const std::size_t i = static_cast<std::size_t>(r.id - 1);
      if (i < w.crater_coverage_pct.size()) std::printf(", layer 1 covers %.1f %%", w.crater_coverage_pct[i]);
      std::printf("\n");
    }
    std::printf("rims          %zu (%zu closed along the border)", w.rims.size(), w.border_rims);
    for (std::size_t k = 0; k < w.rims.size() && k < 6; ++k) std::printf(" (%.3f mm)", w.rims[k].length_mm());
    if (w.rims.size() > 6) std::printf(" ...");
    std::printf(", %zu open pieces\n", w.open_curves);
    if (w.layers == 0) return;
    std::printf("damage cover  %.2f %% (damaged nodes within half a bead width, %.3f mm, of a layer-1 path)\n",
                w.damage_coverage_pct, 0.5 * w.bead_width_mm);
    std::printf("overlap mm    ");
    for (double mm : w.overlap_mm) std::printf(" %.1f", mm);
    std::printf("  (by layer: path length within half a bead of another path of the layer)\n");
    std::printf("layers        %d, paths %zu (%zu half-step paths before clipping)\n", w.layers, w.paths.size(),
                w.half_step_paths);
    std::printf("length        %.3f mm in total\n", w.total_length_mm);
    std::printf("spacing       max error %.4f %%\n", w.spacing_error_pct_max);
    std::printf("chord error   max %.6f mm\n", w.chord_error_mm_max);
    std::printf("coverage %%    ");
    for (double pct : w.coverage_pct) std::printf(" %.2f", pct);
    std::printf("  (by layer: share of its region within half a bead width of its paths)\n");
    std::printf("loops removed %zu, cusps removed %zu, crossings cut %zu, Newton offsets %zu\n", w.loops_removed,
                w.cusps_removed, w.crossings_cut, w.newton_offsets);
    std::printf("out           %s\n", job.out_path.empty() ? "(none)" : job.out_path.c_str());
  }

  WeldLayersJobOptions o_;
  std::string report_;
  std::string bias_ = "check";
  bool from_border_ = false;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(WeldLayersCommand, "weld-layers",
                "Boundary of eroded craters and parallel weld paths layer by layer (Simas, Dias & Guenther)")

}  // namespace conform::app
