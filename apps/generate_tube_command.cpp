// `conform generate tube`: a synthetic tube scan with deformations and scanner effects, and its ground truth
// (pipelines/generate/generate_tube.h). Parses the flags into a GenerateTubeRequest
// (pipelines/generate/generate_tube_json.h, which maps degrees to the API's radians), prints what was made.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "conform/core/error.h"
#include "conform/pipelines/generate/generate_tube.h"
#include "conform/pipelines/generate/generate_tube_json.h"
#include "number_list.h"
#include "terminal.h"

namespace conform::app {
namespace {

Eigen::Vector3d parse_vector(const std::string& text, const std::string& flag) {
  const std::vector<double> v = parse_numbers(text, 3, flag, "x,y,z");
  return {v[0], v[1], v[2]};
}

class GenerateTubeCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.description("Synthetic tube scan (patch or full tube, outer or inner surface) with ground truth beside it");
    c.add_option("--out", out_, "Mesh to write, .ply or .stl; the truth goes to <name>.truth.json; required")
        ->required();
    configure_geometry(c);
    configure_deformations(c);
    configure_effects(c);
    c.add_option("--seed", seed_, "Seed of every random choice (noise, holes, outliers)");
    c.add_flag("--ascii", ascii_, "Write ascii .ply/.stl");
    c.add_flag("--double", double_, "Write .ply vertices as double (the exact truth on disk)");
    c.add_flag("--normals", normals_, "Store per-vertex normals (area-weighted from the faces)");
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
    c.add_flag("--quiet", quiet_, "No progress on stderr");
  }

  int run() override {
    GenerateTubeOptions options = generate_tube_options(request());
    options.tube.progress = stderr_progress(quiet_);
    const GenerateTubeResult result = run_generate_tube(options);
    if (json_) {
      print_json(generate_tube_json(result));
    } else {
      print_text(result);
    }
    return 0;
  }

 private:
  void configure_geometry(CLI::App& c) {
    c.add_option("--radius", t_.radius_mm, "Nominal radius R, mm");
    c.add_option("--length", t_.length_mm, "Length along the axis, mm; the tube spans z in [-L/2, L/2]");
    c.add_option("--arc-deg", arc_deg_, "Azimuth span, deg, in (0, 360]; 360 is a closed tube");
    c.add_option("--arc-center-deg", arc_center_deg_, "Azimuth at the middle of a patch, deg");
    c.add_flag("--inner", inner_, "Inner surface: faces point towards the axis; default outer (away from it)");
    CLI::Option* edge = c.add_option("--edge", t_.edge_mm, "Target edge length of the triangles, mm");
    c.add_option("--vertices", t_.vertex_count, "Choose the edge length for about N vertices instead of --edge")
        ->excludes(edge);
    c.add_option("--axis-point", axis_point_, "Middle of the tube axis, world mm, x,y,z");
    c.add_option("--axis-direction", axis_direction_, "Tube axis (its +z), world, x,y,z");
    c.add_option("--azimuth-reference", azimuth_reference_,
                 "World direction whose part across the axis is azimuth 0, x,y,z; default the world axis least "
                 "aligned with the tube axis (x, then y, then z)");
  }

  void configure_deformations(CLI::App& c) {
    c.add_option("--ovality", t_.ovality_mm,
                 "Ovality amplitude a in r = R + a cos 2(theta - theta0), mm "
                 "(D_max - D_min = 4a)");
    c.add_option("--ovality-azimuth-deg", ovality_azimuth_deg_, "theta0, where the radius is largest, deg");
    c.add_option("--seam-height", t_.seam_height_mm, "Peaking at the seam, radial, mm, signed (+ outwards)");
    c.add_option("--seam-width", t_.seam_width_mm, "Full base width of the seam ridge, arc length mm");
    c.add_option("--seam-azimuth-deg", seam_azimuth_deg_, "Azimuth of the seam, deg");
    c.add_option("--bump", bumps_,
                 "AZ_DEG,Z_MM,HEIGHT_MM,RADIUS_MM: a bump (height > 0) or indentation (< 0), raised cosine of the "
                 "given footprint radius; repeatable")
        ->allow_extra_args(false);
    c.add_option("--bow", t_.bow_mm, "Bow: sagitta at mid-length, mm (zero at both ends, parabolic)");
    c.add_option("--bow-azimuth-deg", bow_azimuth_deg_, "Direction the middle moves to, deg");
  }

  void configure_effects(CLI::App& c) {
    c.add_option("--noise", t_.noise_mm, "Noise, mm: gaussian sigma or uniform half-width");
    c.add_option("--noise-type", noise_type_, "gaussian or uniform")->check(CLI::IsMember({"gaussian", "uniform"}));
    c.add_option("--noise-direction", noise_direction_,
                 "normal (along the exact surface normal) or isotropic (uniform: in a ball)")
        ->check(CLI::IsMember({"normal", "isotropic"}));
    c.add_option("--hole", holes_, "AZ_DEG,Z_MM,RADIUS_MM: a missing disc of the scan; repeatable")
        ->allow_extra_args(false);
    c.add_option("--holes", t_.random_holes, "Number of holes at seeded random places (not overlapping)");
    c.add_option("--hole-radius", t_.random_hole_radius_mm, "Radius of the random holes, mm");
    c.add_option("--outliers", t_.outlier_fraction, "Share of vertices made outliers, in [0, 1)");
    c.add_option("--outlier-distance", t_.outlier_distance_mm,
                 "Outliers move d to 2d along the normal, either side, mm");
  }

  GenerateTubeRequest request() const {
    GenerateTubeRequest r;
    r.tube = t_;
    r.out_path = out_;
    r.arc_deg = arc_deg_;
    r.arc_center_deg = arc_center_deg_;
    r.inner = inner_;
    r.ovality_azimuth_deg = ovality_azimuth_deg_;
    r.seam_azimuth_deg = seam_azimuth_deg_;
    r.bow_azimuth_deg = bow_azimuth_deg_;
    r.noise_type = noise_type_;
    r.noise_direction = noise_direction_;
    r.seed = seed_;
    for (const std::string& text : bumps_) {
      const std::vector<double> v = parse_numbers(text, 4, "--bump", "AZ_DEG,Z_MM,HEIGHT_MM,RADIUS_MM");
      r.bumps.push_back({v[0], v[1], v[2], v[3]});
    }
    for (const std::string& text : holes_) {
      const std::vector<double> v = parse_numbers(text, 3, "--hole", "AZ_DEG,Z_MM,RADIUS_MM");
      r.holes.push_back({v[0], v[1], v[2]});
    }
    r.axis_point = parse_vector(axis_point_, "--axis-point");
    r.axis_direction = parse_vector(axis_direction_, "--axis-direction");
    if (!azimuth_reference_.empty()) r.azimuth_reference = parse_vector(azimuth_reference_, "--azimuth-reference");
    r.ascii = ascii_;
    r.double_precision = double_;
    r.normals = normals_;
    return r;
  }

  static void print_text(const GenerateTubeResult& r) {
    const nlohmann::json& g = r.truth["geometry"];
    const nlohmann::json& m = r.truth["mesh"];
    const nlohmann::json& noise = r.truth["scanner"]["noise"];
    std::printf("mesh       %s (%zu vertices, %zu faces)\n", r.mesh_path.c_str(), r.vertices, r.faces);
    std::printf("truth      %s\n", r.truth_path.c_str());
    std::printf("tube       R %g mm, length %g mm, arc %g deg, %s surface\n", g["radius_mm"].get<double>(),
                g["length_mm"].get<double>(), g["arc_deg"].get<double>(), g["surface"].get<std::string>().c_str());
    std::printf("triangles  edge %.4f mm: %d columns x %d rows\n", m["edge_mm"].get<double>(), m["columns"].get<int>(),
                m["rows"].get<int>());
    const nlohmann::json& a = g["axis_point_mm"];
    const nlohmann::json& d = g["axis_direction"];
    std::printf("axis       point %.6f %.6f %.6f mm, direction %.9f %.9f %.9f\n", a[0].get<double>(),
                a[1].get<double>(), a[2].get<double>(), d[0].get<double>(), d[1].get<double>(), d[2].get<double>());
    if (noise["scale_mm"].get<double>() > 0.0) {
      std::printf("noise      %s %g mm, %s\n", noise["distribution"].get<std::string>().c_str(),
                  noise["scale_mm"].get<double>(), noise["direction"] == "normal" ? "along the normal" : "isotropic");
    } else {
      std::printf("noise      none\n");
    }
    std::printf("holes      %zu, outliers %zu\n", r.holes, r.outliers);
    std::printf("area mm2   %.3f\n", r.surface_area_mm2);
  }

  TubeOptions t_;
  std::string out_;
  double arc_deg_ = 360.0;
  double arc_center_deg_ = 0.0;
  bool inner_ = false;
  std::string axis_point_ = "0,0,0";
  std::string axis_direction_ = "0,0,1";
  std::string azimuth_reference_;
  double ovality_azimuth_deg_ = 0.0;
  double seam_azimuth_deg_ = 0.0;
  std::vector<std::string> bumps_;
  double bow_azimuth_deg_ = 0.0;
  std::string noise_type_ = "gaussian";
  std::string noise_direction_ = "normal";
  std::vector<std::string> holes_;
  std::uint64_t seed_ = 1;
  bool ascii_ = false;
  bool double_ = false;
  bool normals_ = false;
  bool json_ = false;
  bool quiet_ = false;
};

}  // namespace

// Registered inside conform::app, where the command's type is visible to the macro.
CONFORM_COMMAND(GenerateTubeCommand, "generate tube",
                "Synthetic tube scan (ovality, seam peaking, bumps, bow, noise, holes, outliers) with ground truth")

}  // namespace conform::app
