#pragma once
// The pipe protocol between read_cad() and its CAD reader child process (cad_child.cpp): length-prefixed messages,
// native byte order (both ends are the same binary). What the parent receives is untrusted input, since the child
// runs OpenCASCADE on a hostile file: every count is checked against the bytes, every index against the vertices,
// every number for finiteness, before it becomes a Mesh.
//
// A message is [kind: 1 byte][payload length: u64][payload]:
//   'P' progress   [fraction: f64][stage: the rest]
//   'R' result     [unit: u32 n, n bytes][mm_per_unit: f64][vertices: u64 n, 3n f64][triangles: u64 n, 3n i32]
//                  [bodies: u64 n, n x (kind i32, faces u64, triangles u64, failed u64, box 6 f64, volume f64,
//                  flipped i32)][warnings: u32 n, n bytes]
//                  [triangle faces: u64 n (= triangles), n i32][faces: u64 n, n x (surface i32, reversed i32,
//                  sense i32, body u64, triangles u64, area f64, centre 3 f64, origin 3 f64, axis 3 f64, radius f64,
//                  minor radius f64, half angle f64)]
//   'E' error      [category: 1 byte, CadChildError][text: the rest]
//   'S' crash note [signal: i32][VmPeak, kB: u64], written by the child's signal handler before it dies

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "conform/core/cad_plugin_abi.h"
#include "conform/core/mesh.h"

namespace conform::detail {

enum class CadChildError : std::uint8_t {
  kRead = 0,    // the plugin's reason about the file (without the path)
  kMemory = 1,  // out of memory under the child's limit
  kLoad = 2,    // any other exception in the child: the message stands alone
};

constexpr std::size_t kCadWireHeader = 9;

// Messages, each with its header, ready to write.
std::string cad_progress_message(const char* stage, double fraction);
std::string cad_result_message(const conform_cad_result& result);
std::string cad_error_message(CadChildError category, const std::string& text);

struct CadWireResult {
  std::string file_unit;
  double mm_per_file_unit = 1.0;
  Mesh mesh;  // unwelded, as the plugin gave it
  std::vector<conform_cad_body> bodies;
  std::string warnings;  // '\n'-separated
  std::vector<std::int32_t> triangle_faces;  // per triangle of `mesh`, the index into faces
  std::vector<conform_cad_face> faces;
};

// Decodes an 'R' payload. Returns false with `why` set when it is inconsistent: sizes that do not add up to the
// payload, a vertex index out of range, a coordinate that is not finite, an unknown body kind, per-body counts that
// do not add up to the totals, or more triangles than `max_triangles`; for the faces: a triangle's face out of
// range, an unknown surface, a body out of range, a number that is not finite, an analytic surface's axis that is not
// a unit vector or a radius or angle out of its range, per-face triangle counts that do not match the triangles'
// faces, per-body face counts that do not add up.
bool decode_cad_result(const char* payload, std::size_t size, std::size_t max_triangles, CadWireResult* out,
                       std::string* why);

}  // namespace conform::detail
