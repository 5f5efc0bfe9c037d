// `conform generate plate` and `conform generate nosecone`: a deformed composite panel with an opening, its scan,
// its nominal contour, surface and deburring trajectory, and the deformed trajectory as ground truth
// (pipelines/generate/generate_panel.h). One file for both: they share every option but the shape's own.

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "conform/pipelines/generate/generate_panel_json.h"
#include "terminal.h"

namespace conform::app {
namespace {

class GeneratePanelCommand : public Command {
 public:
  explicit GeneratePanelCommand(PanelShape shape) { o_.shape = shape; }

  void configure(CLI::App& c) override {
    c.add_option("--out", out_,
                 "Scan to write, .ply; beside it <name>.nominal.ply, .contour.csv, .trajectory.csv, .truth.csv, "
                 ".truth.json; required")
        ->required();
    if (o_.shape == PanelShape::kPlate) {
      configure_plate(c);
    } else {
      configure_nosecone(c);
    }
    c.add_option("--band", o_.band_mm, "Nominal surface and scan: the panel within this of the opening, mm");
    c.add_option("--thickness", o_.thickness_mm, "Depth of the opening's flank (the panel's edge), mm");
    c.add_option("--surface-edge", o_.surface_edge_mm, "Edge length of the nominal surface mesh, mm");
    c.add_option("--contour-spacing", o_.contour_spacing_mm, "Between contour points, mm");
    c.add_option("--trajectory-spacing", o_.trajectory_spacing_mm, "Between trajectory points, mm");
    c.add_option("--scan-points", o_.scan_points,
                 "Scan points drawn before the missing parts are cut; 0: " +
                     std::to_string(default_scan_points(o_.shape)));
    c.add_option("--noise", o_.noise_mm, "Gaussian noise along the surface normal, sigma, mm");
    c.add_option("--missing", o_.missing_fraction, "Share of the contour's length with no scan near it, in [0, 0.9]");
    c.add_option("--missing-patches", o_.missing_patches, "Arcs the missing share is split into");
    c.add_option("--missing-depth", o_.missing_depth_mm, "How far from the edge a missing arc reaches, mm");
    c.add_option("--holes", o_.holes, "Missing discs of the scan at seeded places");
    c.add_option("--hole-radius", o_.hole_radius_mm, "Radius of those discs, mm");
    c.add_option("--field", o_.field_mm,
                 "Smooth seeded non-rigid field: at most this along the surface normal (z), half of it in the plane, "
                 "mm");
    c.add_option("--field-wavelength", o_.field_wavelength_mm, "The field's shortest wavelength, mm");
    c.add_flag("!--no-flank-scan", o_.scan_flank,
               "One-sided scan: the band on the material side only, not the opening's flank");
    c.add_option("--stray", o_.stray_fraction,
                 "Share of the scan moved 1-20 mm off the surface (stray points), in [0, 0.2]");
    c.add_option("--stripes", o_.stripe_spacing_mm,
                 "A laser-stripe scan: the points on planes across x this far apart, mm (0: spread evenly)");
    c.add_option("--stripe-angle-deg", o_.stripe_angle_deg,
                 "The stripes' planes turned about z from across x by this angle, degrees, in [-90, 90]");
    c.add_option("--rotation-deg", rotation_, "The part's rigid motion: rotation vector, degrees (3 numbers)")
        ->expected(3);
    c.add_option("--translation", translation_, "The part's rigid motion: translation, mm (3 numbers)")->expected(3);
    c.add_option("--seed", o_.seed, "Seed of the scan's sampling, noise and missing parts");
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
    c.add_flag("--quiet", quiet_, "No progress on stderr");
  }

  int run() override {
    GeneratePanelOptions options;
    options.panel = o_;
    options.panel.opening = plate_opening(opening_);
    if (rotation_.size() == 3) options.panel.rotation_deg = Eigen::Vector3d(rotation_[0], rotation_[1], rotation_[2]);
    if (translation_.size() == 3)
      options.panel.translation_mm = Eigen::Vector3d(translation_[0], translation_[1], translation_[2]);
    options.out_path = out_;
    options.panel.progress = stderr_progress(quiet_);
    const GeneratePanelResult r = run_generate_panel(options);
    if (json_) {
      print_json(generate_panel_json(r));
      return 0;
    }
    std::printf("scan        %s (%zu points)\n", r.files.scan.c_str(), r.scan_points);
    std::printf("nominal     %s (%zu vertices, %zu faces)\n", r.files.nominal.c_str(), r.surface_vertices,
                r.surface_faces);
    std::printf("contour     %s (%zu points, %.3f mm)\n", r.files.contour.c_str(), r.contour_points, r.perimeter_mm);
    std::printf("trajectory  %s (%zu rows)\n", r.files.trajectory.c_str(), r.trajectory_rows);
    std::printf("truth       %s, %s\n", r.files.truth_trajectory.c_str(), r.files.truth_json.c_str());
    return 0;
  }

 private:
  void configure_plate(CLI::App& c) {
    c.description("Synthetic double-curvature plate with a porthole, sagging between clamps, scanned around it");
    c.add_option("--radius-x", o_.plate_radius_x_mm, "Curvature radius along x, mm");
    c.add_option("--radius-y", o_.plate_radius_y_mm, "Curvature radius along y, mm");
    c.add_option("--porthole-width", o_.porthole_width_mm, "Porthole along x (diameter when round), mm");
    c.add_option("--porthole-height", o_.porthole_height_mm, "Porthole along y, mm");
    c.add_flag("--round", o_.round, "A round porthole (diameter --porthole-width)");
    c.add_option("--clamp-span", o_.clamp_span_mm, "Distance between the clamps (along x), mm");
    c.add_option("--sag", o_.sag_mm, "Sag at mid-span between the clamps, mm");
    c.add_option("--bend", o_.bend_mm, "Bending across the porthole, mm");
    c.add_option("--twist", o_.twist_mm, "Twist, mm");
    c.add_option("--opening", opening_, "The opening: ellipse (porthole) or rectangle (corners --corner-radius)")
        ->check(CLI::IsMember({"ellipse", "rectangle"}));
    c.add_option("--corner-radius", o_.corner_radius_mm, "Radius of the rectangle's corners, mm (0: sharp)");
    add_dent_options(c);
  }

  void add_dent_options(CLI::App& c) {
    c.add_option("--dent", o_.dent_depth_mm, "A dent at the opening's edge: its depth into the part, mm (0: none)");
    c.add_option("--dent-width", o_.dent_width_mm, "The dent's full width (4 sigma of its Gaussian profile), mm");
    c.add_option("--dent-at", o_.dent_at, "Where the dent is: the angle about the opening's centre, share of a turn");
  }

  void configure_nosecone(CLI::App& c) {
    c.description("Synthetic barrel section with a cockpit-like opening with corners, deformed, scanned around it");
    c.add_option("--radius", o_.barrel_radius_mm, "Barrel radius, mm");
    c.add_option("--window-height", o_.window_height_mm, "Opening along the axis, mm");
    c.add_option("--window-bottom", o_.window_bottom_mm, "Opening's width (arc length) at its rear edge, mm");
    c.add_option("--window-top", o_.window_top_mm, "Opening's width at its front edge, mm");
    c.add_option("--corner-radius", o_.corner_radius_mm, "Radius of the opening's corners, mm (0: sharp)");
    c.add_option("--ovality", o_.ovality_mm, "Ovality of the cross-section, mm");
    c.add_option("--droop", o_.droop_mm, "Droop of the front end, mm");
    add_dent_options(c);
  }

  PanelOptions o_;
  std::vector<double> rotation_, translation_;
  std::string opening_ = "ellipse";
  std::string out_;
  bool json_ = false;
  bool quiet_ = false;
};

class GeneratePlateCommand : public GeneratePanelCommand {
 public:
  GeneratePlateCommand() : GeneratePanelCommand(PanelShape::kPlate) {}
};

class GenerateNoseconeCommand : public GeneratePanelCommand {
 public:
  GenerateNoseconeCommand() : GeneratePanelCommand(PanelShape::kNoseCone) {}
};

}  // namespace

CONFORM_COMMAND(GeneratePlateCommand, "generate plate",
                "Synthetic deformed plate with a porthole: scan, nominal contour/surface/trajectory, ground truth")
CONFORM_COMMAND(
    GenerateNoseconeCommand, "generate nosecone",
    "Synthetic deformed barrel with a cockpit-like opening: scan, nominal contour/surface/trajectory, truth")

}  // namespace conform::app
