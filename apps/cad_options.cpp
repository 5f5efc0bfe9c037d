#include "cad_options.h"

#include <cmath>

#include "terminal.h"

namespace conform::app {

void add_cad_options(CLI::App& command, CadReadOptions& cad) {
  command.add_option("--cad-deflection", cad.deflection_mm,
                     "STEP/IGES references: chordal deflection of the tessellation, mm (no triangle farther from the "
                     "CAD surface)");
  command
      .add_option_function<double>(
          "--cad-angle-deg", [&cad](double deg) { cad.angular_deflection_rad = deg * M_PI / 180.0; },
          "STEP/IGES references: angular deflection, deg; default matched to --cad-deflection (the angle of a chord "
          "with that sagitta on a 1 mm radius)")
      ->check(CLI::Range(0.0, 90.0));
  // A damaged file ends as exit 2 naming what happened, not as a crash or a run of hours (core/cad.h).
  command.add_option("--cad-timeout", cad.timeout_s,
                     "STEP/IGES references: wall-clock limit of reading and tessellating one file, s (it runs in a "
                     "child process; over the limit it is stopped, exit 2)")
      ->check(CLI::Range(1e-3, 86400.0));
  command.add_option("--cad-memory-mib", cad.memory_limit_mib,
                     "STEP/IGES references: memory the CAD reader may use, MiB (address space; over it, exit 2)")
      ->check(CLI::Range(std::size_t{64}, std::size_t{1} << 20));
  command.add_option("--cad-max-triangles", cad.max_triangles,
                     "STEP/IGES references: refuse a tessellation estimated (before meshing) to need more triangles")
      ->check(CLI::Range(std::size_t{1}, std::size_t{200'000'000}));
  command.add_option("--cad-save-mesh", cad.save_mesh_path,
                     "STEP/IGES references: also write the tessellation used (mm, welded) to this .ply, .stl or .obj "
                     "file, to see it or to reuse it without tessellating again");
}

void print_cad_text(const std::vector<CadReport>& reports, std::FILE* out) {
  for (const CadReport& r : reports) std::fprintf(out, "cad           %s\n", r.summary().c_str());
}


}  // namespace conform::app
