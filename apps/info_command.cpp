// `conform info FILE`: points, faces, normals, bounding box and non-finite count of a cloud or mesh file.

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>

#include "cad_options.h"
#include "command.h"
#include "conform/core/error.h"
#include "conform/core/units.h"
#include "conform/pipelines/info/info.h"
#include "json_values.h"
#include "terminal.h"

namespace conform::app {
namespace {

class InfoCommand : public Command {
 public:
  void configure(CLI::App& command) override {
    command
        .add_option("file", options_.path,
                    "Cloud, mesh or CAD file (.ply .stl .obj .pcd .xyz .txt .asc .csv; .step .stp .iges .igs)")
        ->required();
    command.add_option("--units", units_,
                       "Units of a mesh or cloud file (mm, cm, m, in); the box and area are shown in mm (a CAD file "
                       "says its own)");
    add_cad_options(command, options_.cad);
    command.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override {
    files.add_input(options_.path);
    files.add_output(options_.cad.save_mesh_path);
  }

  int run() override {
    options_.mm_per_unit = millimetres_per_unit(units_);
    options_.cad.progress = stderr_progress(json_);
    const InfoResult info = run_info(options_);
    warn_all(info.warnings);
    if (json_) {
      nlohmann::json j = {{"file", info.path},
                  {"format", info.format},
                  {"units", info.cad.read ? info.cad.file_unit : units_},
                  {"points", info.points},
                  {"faces", info.faces},
                  {"has_normals", info.has_normals},
                  {"non_finite_points", info.non_finite},
                  {"bounding_box_min_mm", to_json(info.box.min, info.box.empty())},
                  {"bounding_box_max_mm", to_json(info.box.max, info.box.empty())},
                  {"bounding_box_size_mm", to_json(info.box.size(), info.box.empty())},
                  {"surface_area_mm2", info.surface_area_mm2}};
      if (info.cad.read) j["cad"] = cad_json({info.cad}).front();
      print_json(j);
    } else {
      print_text(info, units_);
      if (info.cad.read) print_cad_bodies(info.cad);
    }
    if (info.points == 0) throw Error(info.path + ": holds no points");
    if (info.non_finite > 0) {
      throw Error(info.path + ": " + std::to_string(info.non_finite) +
                  " points have NaN or infinite coordinates; jobs refuse such a file");
    }
    return 0;
  }

 private:
  static void print_text(const InfoResult& info, const std::string& units) {
    std::printf("file         %s\n", info.path.c_str());
    std::printf("format       %s\n", info.format.c_str());
    if (!info.cad.read) std::printf("units        %s\n", units.c_str());
    std::printf("points       %zu\n", info.points);
    std::printf("faces        %zu\n", info.faces);
    std::printf("normals      %s\n", info.has_normals ? "yes" : "no");
    std::printf("non-finite   %zu\n", info.non_finite);
    if (!info.box.empty()) {
      const auto& lo = info.box.min;
      const auto& hi = info.box.max;
      const Eigen::Vector3d size = info.box.size();
      std::printf("box min mm   %.4f %.4f %.4f\n", lo.x(), lo.y(), lo.z());
      std::printf("box max mm   %.4f %.4f %.4f\n", hi.x(), hi.y(), hi.z());
      std::printf("box size mm  %.4f %.4f %.4f\n", size.x(), size.y(), size.z());
    }
    if (info.faces > 0) std::printf("area mm2     %.4f\n", info.surface_area_mm2);
  }

  // The CAD file's bodies, one line each, and the tessellation the jobs would use.
  static void print_cad_bodies(const CadReport& cad) {
    std::printf("cad unit     %s (x%g to mm)\n", cad.file_unit.c_str(), cad.mm_per_file_unit);
    std::printf("tessellation deflection %g mm, angle %.4g deg: %zu triangles from %zu faces\n", cad.deflection_mm,
                cad.angular_deflection_rad * 180.0 / M_PI, cad.triangles, cad.faces);
    for (std::size_t i = 0; i < cad.bodies.size(); ++i) {
      const CadBody& b = cad.bodies[i];
      std::printf("body %-7zu %s, %zu faces, %zu triangles, box %.4f %.4f %.4f .. %.4f %.4f %.4f mm", i + 1,
                  to_string(b.kind), b.faces, b.triangles, b.box_min_mm[0], b.box_min_mm[1], b.box_min_mm[2],
                  b.box_max_mm[0], b.box_max_mm[1], b.box_max_mm[2]);
      if (b.kind == CadBodyKind::kSolid) std::printf(", volume %.4f mm3%s", b.volume_mm3, b.flipped ? " (flipped)" : "");
      std::printf("\n");
    }
    if (!cad.saved_mesh_path.empty()) std::printf("wrote        %s\n", cad.saved_mesh_path.c_str());
  }

  InfoOptions options_;
  std::string units_ = "mm";
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(InfoCommand, "info", "Show what a cloud, mesh or CAD file holds (points, faces, normals, box, NaNs; CAD bodies)")

}  // namespace conform::app
