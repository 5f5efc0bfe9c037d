#pragma once
// CAD references (STEP, IGES) read as a triangle mesh with a stated chordal deflection, through the cad plugin
// (cad/, OpenCASCADE; loaded on the first CAD file, core/include/conform/core/plugin.h). read_geometry() and
// read_mesh() call this for .step .stp .iges .igs, so every job that reads a reference surface reads CAD too.
// Units come from the file and are converted to mm; the faces are wound so that outside is positive.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "conform/core/mesh.h"
#include "conform/core/progress.h"

namespace conform {

struct CadReadOptions {
  // Chordal deflection of the tessellation, mm: no point of a triangle is farther than this from the CAD surface.
  // The chords of a curved face lie inside it: points on it deviate by up to this much more, on average about 1/3 of
  // it (docs/cad.md, measured), invisible next to a good scan's noise (HandySCAN ~0.02 mm). Finer costs time: a
  // torus of 30 x 8 mm takes 3 s at 0.005 mm and 35 s at 0.001 mm (345k triangles).
  double deflection_mm = 0.005;
  // Angular deflection, rad; 0: matched to deflection_mm (the angle whose chord on a 1 mm radius has that sagitta,
  // at most 0.5 rad), so only features smaller than 1 mm in radius are limited by the angle.
  double angular_deflection_rad = 0.0;
  ProgressFn progress;  // stages "read CAD", "tessellate CAD"
  // Not empty: read_cad also writes the tessellation it returns (welded, mm) to this .ply (double precision), .stl or
  // .obj file, atomically (core/atomic_file.h: inside a command's OutputSet, committed with its other outputs), so
  // that a user can see and reuse the mesh conform measured against. Not written when reading fails.
  std::string save_mesh_path;

  // Isolation (issue 32): OpenCASCADE runs in a child process (core/src/cad_child.h), so that a damaged file that
  // crashes it, grows without bound or loops ends as a conform::Error naming the file, never as a crash of conform.
  // Wall-clock limit of the read and tessellation, s: a valid part of a few thousand faces takes seconds (docs/cad.md),
  // and a face listed a million times in a hostile STEP would otherwise run for many minutes.
  double timeout_s = 120.0;
  // Address space the reader may add to what it inherits, MiB (RLIMIT_AS): room for the triangle budget below on
  // doubly curved faces, where OpenCASCADE 7.6's mesher peaks at about 3.6 KiB per triangle (docs/cad.md, measured).
  std::size_t memory_limit_mib = 4096;
  // A tessellation estimated (before meshing, from each face's area and curvature) or found to need more triangles is
  // refused, naming the estimate and the deflection that would fit. One million: three times the largest part
  // measured in docs/cad.md (357k triangles), about what the mesher builds within the memory limit above on doubly
  // curved faces (1.1 million at 3.6 KiB) and within the time limit (a sphere's 201k triangles take 13 s).
  std::size_t max_triangles = 1'000'000;

  // False (and why) for a deflection that is not finite and in [1e-4, 10] mm, a negative angular deflection, a
  // save_mesh_path that is not .ply, .stl or .obj, a timeout not in (0, 86400] s, a memory limit under 64 MiB or over
  // 1 TiB, or a triangle budget of 0 or over 200 million.
  bool IsValid(std::string* error) const;
  double angular_deflection() const;  // as used (resolved when 0)
};

enum class CadBodyKind { kSolid, kOpenShell, kFreeFaces };
const char* to_string(CadBodyKind kind);  // "solid", "open shell", "free faces"

struct CadBody {
  CadBodyKind kind = CadBodyKind::kSolid;
  std::size_t faces = 0;  // CAD faces
  std::size_t triangles = 0;
  std::size_t failed_faces = 0;  // faces the tessellation gave no triangles
  std::array<double, 3> box_min_mm{};
  std::array<double, 3> box_max_mm{};
  double volume_mm3 = 0.0;  // solids: enclosed by the tessellation
  bool flipped = false;     // its faces pointed inwards in the file and were reversed
};

// What was read from a CAD file; `read` is false for every other format.
struct CadReport {
  bool read = false;
  std::string path;
  std::string format;            // "STEP" or "IGES"
  std::string file_unit;         // as written in the file: "MM", "M", "INCH", ...
  double mm_per_file_unit = 1.0;
  double deflection_mm = 0.0;    // as used
  double angular_deflection_rad = 0.0;
  std::size_t faces = 0;         // CAD faces over all bodies
  std::size_t triangles = 0;     // after welding
  std::size_t vertices = 0;
  std::vector<CadBody> bodies;
  std::string saved_mesh_path;   // where the tessellation was written (CadReadOptions::save_mesh_path), or empty

  std::string summary() const;  // one line: "part.step: STEP in MM, 3 solids, 42 faces -> 1234 triangles (0.005 mm ...)"
};

// True for .step .stp .iges .igs (case-insensitive).
bool is_cad_file(const std::string& path);

// The file's bodies as one mesh (mm, placements applied, coincident vertices welded). Throws conform::Error naming
// the file and the reason: not a STEP/IGES file, no faces, a failed tessellation, the plugin missing. Warnings
// (open shells, faces without triangles, flipped solids) go to `warnings`, each naming the file.
Mesh read_cad(const std::string& path, const CadReadOptions& options, CadReport* report,
              std::vector<std::string>* warnings);

}  // namespace conform
