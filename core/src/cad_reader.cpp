// CAD files through the cad plugin: the file is checked here (a regular file, the format's signature) before the
// plugin, and OpenCASCADE behind it, is loaded at all; OpenCASCADE then reads only in a child process (cad_child.h).

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cad_child.h"
#include "conform/core/cad.h"
#include "conform/core/cad_faces.h"
#include "conform/core/cad_plugin_abi.h"
#include "conform/core/error.h"
#include "conform/core/input_file.h"
#include "conform/core/io.h"
#include "conform/core/mesh_weld.h"
#include "conform/core/triangle_index.h"

namespace conform {

namespace {

bool is_step_extension(const std::string& extension) { return extension == ".step" || extension == ".stp"; }

// STEP (ISO 10303-21) files start with "ISO-10303-21;" (after an optional byte-order mark and blank space).
bool looks_like_step(const std::string& bytes) {
  std::size_t i = bytes.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
  return bytes.compare(i, 12, "ISO-10303-21") == 0;
}

// IGES files are 80-column records; the first is a Start (S) or, rarely, a Flag (F) record: column 73 says which.
bool looks_like_iges(const std::string& bytes) {
  if (bytes.size() < 73) return false;
  const char section = bytes[72];
  const std::size_t newline = bytes.find('\n');
  return (section == 'S' || section == 'F' || section == 'C') && (newline == std::string::npos || newline >= 72);
}

std::string trimmed_unit(const std::string& unit) {
  std::string out = unit.substr(0, std::min(unit.find('\0'), sizeof(conform_cad_result::file_unit)));
  while (!out.empty() && (out.back() == ' ' || out.back() == '\'')) out.pop_back();
  while (!out.empty() && (out.front() == ' ' || out.front() == '\'')) out.erase(out.begin());
  return out.empty() ? "unknown" : out;
}

CadBody body_of(const conform_cad_body& b) {
  CadBody body;
  body.kind = b.kind == CONFORM_CAD_SOLID        ? CadBodyKind::kSolid
              : b.kind == CONFORM_CAD_OPEN_SHELL ? CadBodyKind::kOpenShell
                                                 : CadBodyKind::kFreeFaces;
  body.faces = b.faces;
  body.triangles = b.triangles;
  body.failed_faces = b.failed_faces;
  for (int k = 0; k < 3; ++k) {
    body.box_min_mm[static_cast<std::size_t>(k)] = b.box_min_mm[k];
    body.box_max_mm[static_cast<std::size_t>(k)] = b.box_max_mm[k];
  }
  body.volume_mm3 = b.volume_mm3;
  body.flipped = b.flipped != 0;
  return body;
}

}  // namespace

bool CadReadOptions::IsValid(std::string* error) const {
  std::string why;
  if (!(std::isfinite(deflection_mm) && deflection_mm >= 1e-4 && deflection_mm <= 10.0)) {
    why = "the CAD deflection must be between 0.0001 and 10 mm, not " + std::to_string(deflection_mm);
  } else if (!(std::isfinite(angular_deflection_rad) && angular_deflection_rad >= 0.0)) {
    why = "the CAD angular deflection must be >= 0 rad";
  } else if (!(std::isfinite(timeout_s) && timeout_s > 0.0 && timeout_s <= 86400.0)) {
    why = "the CAD time limit must be more than 0 and at most 86400 s, not " + std::to_string(timeout_s);
  } else if (memory_limit_mib < 64 || memory_limit_mib > (std::size_t{1} << 20)) {
    why = "the CAD memory limit must be between 64 MiB and 1 TiB, not " + std::to_string(memory_limit_mib) + " MiB";
  } else if (max_triangles == 0 || max_triangles > 200'000'000) {
    why = "the CAD triangle budget must be between 1 and 200 million, not " + std::to_string(max_triangles);
  } else if (!save_mesh_path.empty()) {
    const std::string e = file_extension(save_mesh_path);
    if (e != ".ply" && e != ".stl" && e != ".obj") {
      why = save_mesh_path + ": the tessellation is saved as .ply, .stl or .obj, not '" + e + "'";
    }
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

double CadReadOptions::angular_deflection() const {
  if (angular_deflection_rad > 0.0) return angular_deflection_rad;
  // The sagitta of a chord through angle a on radius r is r (1 - cos(a / 2)); r = 1 mm.
  const double r_mm = 1.0;
  return std::min(0.5, 2.0 * std::acos(1.0 - std::min(deflection_mm / r_mm, 1.0)));
}

const char* to_string(CadBodyKind kind) {
  switch (kind) {
    case CadBodyKind::kSolid:
      return "solid";
    case CadBodyKind::kOpenShell:
      return "open shell";
    case CadBodyKind::kFreeFaces:
      return "free faces";
  }
  return "?";
}

std::string CadReport::summary() const {
  std::size_t solids = 0;
  for (const CadBody& b : bodies) solids += b.kind == CadBodyKind::kSolid ? 1 : 0;
  char text[512];
  std::snprintf(text, sizeof text,
                "%s in %s (x%g to mm), %zu bodies (%zu solids), %zu faces -> %zu triangles at deflection %g mm, "
                "%.4g rad",
                format.c_str(), file_unit.c_str(), mm_per_file_unit, bodies.size(), solids, faces, triangles,
                deflection_mm, angular_deflection_rad);
  return path + ": " + text + (saved_mesh_path.empty() ? "" : ", saved to " + saved_mesh_path);
}

bool is_cad_file(const std::string& path) {
  const std::string e = file_extension(path);
  return is_step_extension(e) || e == ".iges" || e == ".igs";
}

namespace {

CadFace face_of(const conform_cad_face& f) {
  CadFace face;
  face.type = static_cast<CadSurfaceType>(f.surface);  // range checked by decode_cad_result
  face.reversed = f.reversed != 0;
  face.sense = f.sense;
  face.body = f.body;
  face.area_mm2 = f.area_mm2;
  face.centre_mm = Eigen::Vector3d(f.centre_mm[0], f.centre_mm[1], f.centre_mm[2]);
  face.origin_mm = Eigen::Vector3d(f.origin_mm[0], f.origin_mm[1], f.origin_mm[2]);
  face.axis = Eigen::Vector3d(f.axis[0], f.axis[1], f.axis[2]);
  if (is_analytic(face.type)) face.axis.normalize();  // a unit vector to 1e-6 on the wire; exactly one here
  face.radius_mm = f.radius_mm;
  face.minor_radius_mm = f.minor_radius_mm;
  face.half_angle_rad = f.half_angle_rad;
  return face;
}

// How deep (in chordal deflections of the tessellation, plus a float rounding of the part's size) a triangle of one
// solid must lie inside another to count as an overlap: solids that only touch (an assembly's parts in contact) have
// their faces within the deflection of each other's.
constexpr double kOverlapDeflections = 2.0;

// Solids whose interiors overlap (two parts exported without their boolean union, an assembly whose parts
// interpenetrate): their faces inside each other are measured as surfaces of the part, and points near them take the
// wrong sign. For each pair of solids whose boxes overlap, the triangle centroids of each lying deeper than the bound
// inside the other (signed by the pseudo-normal, core/triangle_index.h) name the pair.
void warn_overlapping_solids(const std::string& path, const CadReport& cad, const Mesh& mesh,
                             const std::vector<std::size_t>& body_of_triangle, std::vector<std::string>* warnings) {
  const std::size_t n = cad.bodies.size();
  const auto overlap = [&](std::size_t i, std::size_t j, double depth) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (cad.bodies[i].box_max_mm[k] <= cad.bodies[j].box_min_mm[k] + depth ||
          cad.bodies[j].box_max_mm[k] <= cad.bodies[i].box_min_mm[k] + depth) {
        return false;
      }
    }
    return true;
  };
  std::vector<std::vector<std::size_t>> triangles(n);  // each body's
  for (std::size_t t = 0; t < body_of_triangle.size(); ++t) {
    if (body_of_triangle[t] < n) triangles[body_of_triangle[t]].push_back(t);
  }
  // Each body's triangle index, built once, when a pair first needs it.
  std::vector<std::unique_ptr<TriangleIndex>> indices(n);
  const auto index_of = [&](std::size_t b) -> const TriangleIndex& {
    if (!indices[b]) {
      Mesh part;
      part.vertices = mesh.vertices;
      for (const std::size_t t : triangles[b]) part.faces.push_back(mesh.faces[t]);
      indices[b] = std::make_unique<TriangleIndex>(part);
    }
    return *indices[b];
  };
  double size = 0.0;
  for (const Eigen::Vector3d& v : mesh.vertices) size = std::max(size, v.cwiseAbs().maxCoeff());
  const double depth = kOverlapDeflections * cad.deflection_mm + 1e-6 * size;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if (cad.bodies[i].kind != CadBodyKind::kSolid || cad.bodies[j].kind != CadBodyKind::kSolid ||
          triangles[i].empty() || triangles[j].empty() || !overlap(i, j, depth)) {
        continue;
      }
      std::size_t inside = 0;
      double deepest = 0.0;
      for (const auto& [a, b] : {std::pair<std::size_t, std::size_t>{i, j}, {j, i}}) {
        const TriangleIndex& index = index_of(b);
        for (const std::size_t t : triangles[a]) {
          const Face& f = mesh.faces[t];
          const Eigen::Vector3d c =
              (mesh.vertices[static_cast<std::size_t>(f[0])] + mesh.vertices[static_cast<std::size_t>(f[1])] +
               mesh.vertices[static_cast<std::size_t>(f[2])]) /
              3.0;
          const SurfacePoint s = index.closest(c);
          const double distance = std::sqrt(s.sq_distance);
          if ((c - s.point).dot(index.normal_at(s)) < 0.0 && distance > depth) {
            ++inside;
            deepest = std::max(deepest, distance);
          }
        }
      }
      if (inside == 0) continue;
      char text[400];
      std::snprintf(text, sizeof(text),
                    ": solids %zu and %zu overlap (%zu of their triangles lie inside the other, up to %.3g mm deep): "
                    "the faces inside are measured as surfaces of the part and points near them take the wrong "
                    "sign. Unite them in CAD (a boolean union) and export one solid",
                    i + 1, j + 1, inside, deepest);
      warnings->push_back(path + text);
    }
  }
}

// read_cad's work; `faces` (when not null) also receives the faces, per welded triangle and per face.
Mesh read_cad_with_faces(const std::string& path, const CadReadOptions& options, CadReport* report_out,
                         std::vector<std::string>* warnings, CadFaces* faces) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(path + ": " + why);
  const std::string bytes = read_input_file(path);
  const bool step = is_step_extension(file_extension(path));
  if (step && !looks_like_step(bytes)) throw Error(path + ": not a STEP file (it does not start with ISO-10303-21)");
  if (!step && !looks_like_iges(bytes)) {
    throw Error(path + ": not an IGES file (its first line is not an 80-column Start record, 'S' in column 73)");
  }
  conform_cad_request request{};
  request.abi_version = CONFORM_CAD_ABI_VERSION;
  request.path = path.c_str();
  request.bytes = bytes.data();
  request.size = bytes.size();
  request.format = step ? CONFORM_CAD_STEP : CONFORM_CAD_IGES;
  request.deflection_mm = options.deflection_mm;
  request.angular_deflection_rad = options.angular_deflection();
  request.max_triangles = options.max_triangles;
  detail::CadWireResult result = detail::read_cad_in_child(path, request, options);
  std::vector<std::size_t> kept;
  MeshWeldResult welded = weld_coincident_vertices(std::move(result.mesh), path, &kept);

  CadReport cad;
  cad.read = true;
  cad.path = path;
  cad.format = step ? "STEP" : "IGES";
  cad.file_unit = trimmed_unit(result.file_unit);
  cad.mm_per_file_unit = result.mm_per_file_unit;
  cad.deflection_mm = options.deflection_mm;
  cad.angular_deflection_rad = request.angular_deflection_rad;
  for (const conform_cad_body& b : result.bodies) {
    cad.bodies.push_back(body_of(b));
    cad.faces += cad.bodies.back().faces;
  }
  cad.triangles = welded.mesh.faces.size();
  cad.vertices = welded.mesh.vertices.size();
  if (warnings != nullptr) {
    const std::string& text = result.warnings;
    for (std::size_t start = 0; start < text.size();) {
      const std::size_t end = std::min(text.find('\n', start), text.size());
      if (end > start) warnings->push_back(path + ": " + text.substr(start, end - start));
      start = end + 1;
    }
  }
  if (warnings != nullptr && cad.bodies.size() > 1 && !result.triangle_faces.empty()) {
    std::vector<std::size_t> body_of_triangle(kept.size());
    for (std::size_t t = 0; t < kept.size(); ++t) {  // in range: checked by decode_cad_result
      body_of_triangle[t] = result.faces[static_cast<std::size_t>(result.triangle_faces[kept[t]])].body;
    }
    warn_overlapping_solids(path, cad, welded.mesh, body_of_triangle, warnings);
  }
  if (faces != nullptr) {
    faces->faces.clear();
    for (const conform_cad_face& f : result.faces) faces->faces.push_back(face_of(f));
    faces->triangle_face.resize(kept.size());
    for (CadFace& f : faces->faces) f.triangles = 0;
    for (std::size_t t = 0; t < kept.size(); ++t) {
      const std::int32_t face = result.triangle_faces[kept[t]];  // in range: checked by decode_cad_result
      faces->triangle_face[t] = face;
      ++faces->faces[static_cast<std::size_t>(face)].triangles;
    }
  }
  if (!options.save_mesh_path.empty()) {
    WriteOptions write;
    write.double_precision = true;  // read back, the same coordinates to the last bit (.ply; .stl is float)
    write_mesh(options.save_mesh_path, welded.mesh, write);
    cad.saved_mesh_path = options.save_mesh_path;
  }
  if (report_out != nullptr) *report_out = cad;
  return std::move(welded.mesh);
}

}  // namespace

Mesh read_cad(const std::string& path, const CadReadOptions& options, CadReport* report_out,
              std::vector<std::string>* warnings) {
  return read_cad_with_faces(path, options, report_out, warnings, nullptr);
}

CadFaces read_cad_faces(const std::string& path, const CadReadOptions& options, CadReport* report,
                        std::vector<std::string>* warnings) {
  CadFaces out;
  out.mesh = read_cad_with_faces(path, options, report, warnings, &out);
  return out;
}

}  // namespace conform
