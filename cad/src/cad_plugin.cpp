// The plugin's C entry points (core/include/conform/core/cad_plugin_abi.h): no exception crosses them.

#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include <Standard_Failure.hxx>

#include "conform/cad/cad_plugin.h"
#include "occt_shape.h"

namespace {

char* copy_text(const std::string& text) {
  char* out = static_cast<char*>(std::malloc(text.size() + 1));
  if (out != nullptr) std::memcpy(out, text.c_str(), text.size() + 1);
  return out;
}

template <class T>
T* copy_array(const std::vector<T>& values) {
  if (values.empty()) return nullptr;
  T* out = static_cast<T*>(std::malloc(values.size() * sizeof(T)));
  if (out == nullptr) throw std::bad_alloc();
  std::memcpy(out, values.data(), values.size() * sizeof(T));
  return out;
}

void fill(const conform::cad::ReadShape& read, const conform::cad::Tessellation& t, conform_cad_result* result) {
  std::strncpy(result->file_unit, read.file_unit.c_str(), sizeof(result->file_unit) - 1);
  result->mm_per_file_unit = read.mm_per_file_unit;
  result->vertices = copy_array(t.vertices);
  result->vertex_count = t.vertices.size() / 3;
  result->triangles = copy_array(t.triangles);
  result->triangle_count = t.triangles.size() / 3;
  result->bodies = copy_array(t.bodies);
  result->body_count = t.bodies.size();
  result->triangle_faces = copy_array(t.triangle_faces);
  result->faces = copy_array(t.faces);
  result->face_count = t.faces.size();
  std::string warnings;
  for (const std::string& w : t.warnings) warnings += w + "\n";
  if (!warnings.empty()) result->warnings = copy_text(warnings);
}

}  // namespace

extern "C" int conform_cad_read(const conform_cad_request* request, conform_cad_result* result) {
  *result = conform_cad_result{};
  try {
    if (request->abi_version != CONFORM_CAD_ABI_VERSION) {
      throw std::runtime_error("the CAD plugin speaks interface version " + std::to_string(CONFORM_CAD_ABI_VERSION) +
                               ", conform " + std::to_string(request->abi_version) + ": reinstall conform");
    }
    const conform::cad::ProgressSink progress{request->progress, request->progress_context};
    const conform::cad::ReadShape read = conform::cad::read_shape(*request, progress);
    const conform::cad::Tessellation t =
        conform::cad::tessellate(read.shape, request->deflection_mm, request->angular_deflection_rad,
                                 request->max_triangles, progress);
    fill(read, t, result);
    return 0;
  } catch (const Standard_Failure& e) {
    result->error = copy_text(std::string("OpenCASCADE failed: ") + e.GetMessageString());
  } catch (const std::bad_alloc&) {
    result->error = copy_text("out of memory while reading or tessellating it (try a larger --cad-deflection)");
  } catch (const std::exception& e) {
    result->error = copy_text(e.what());
  } catch (...) {
    result->error = copy_text("OpenCASCADE failed with an unknown exception");
  }
  return 1;
}

extern "C" void conform_cad_free(conform_cad_result* result) {
  std::free(result->error);
  std::free(result->vertices);
  std::free(result->triangles);
  std::free(result->bodies);
  std::free(result->warnings);
  std::free(result->triangle_faces);
  std::free(result->faces);
  *result = conform_cad_result{};
}
