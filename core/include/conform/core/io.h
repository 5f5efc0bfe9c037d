#pragma once
// Reading and writing clouds and meshes, the format chosen by the file's extension (case-insensitive):
//   .ply  ascii and binary (little/big endian), clouds and meshes, vertex normals (nx, ny, nz)
//   .stl  ascii and binary, meshes (vertices welded where bit-identical)
//   .obj  meshes (v, vn, f; polygons fan-triangulated)
//   .pcd  clouds (ascii, binary, binary_compressed; conform's own reader and writer), normals as normal_x/y/z
//   .xyz .txt .asc .csv  point lists: whitespace- or comma-separated, optional header line naming x y z nx ny nz
//   .step .stp .iges .igs  CAD, read only: tessellated by the cad plugin (cad.h), in mm, outside positive
// Every reader checks counts against the file's size before allocating and reports errors as conform::Error
// naming the file and the line, element or byte where the problem is. Writers are byte-deterministic (the same
// input gives the same bytes: no dates in headers) and atomic.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "conform/core/cad.h"
#include "conform/core/cloud.h"
#include "conform/core/mesh.h"

namespace conform {

// What to do with points that have a NaN or infinite coordinate.
enum class NonFinitePolicy {
  kReject,  // throw conform::Error naming the file, the first bad point and the count
  kDrop,    // remove them (and the faces that use them), with a warning saying how many
  kKeep,    // keep them as they are (for `conform info`, which counts them)
};

struct ReadOptions {
  // Implicit, so that `read_mesh(path, {NonFinitePolicy::kDrop})` stays a complete initialisation.
  ReadOptions(NonFinitePolicy policy = NonFinitePolicy::kReject) : non_finite(policy) {}  // NOLINT(runtime/explicit)

  NonFinitePolicy non_finite;
  CadReadOptions cad;  // .step .stp .iges .igs: the tessellation (deflection) and its progress
};

// What a reader noticed that was not worth an error (dropped points, ignored properties); apps print them.
struct ReadReport {
  std::vector<std::string> warnings;
  std::size_t non_finite_points = 0;  // found in the file (dropped or kept according to the policy)
  CadReport cad;                      // cad.read: the file was CAD (units, bodies, deflection, triangles)
};

enum class Encoding { kBinary, kAscii };

struct WriteOptions {
  Encoding encoding = Encoding::kBinary;  // for .ply, .stl and .pcd; .obj and the point lists are text anyway
  // .ply vertices and normals as double; text formats print each double's shortest round-trip text (up to 17 digits)
  // instead of the float's (up to 9). .stl and .pcd are single precision whatever this says.
  bool double_precision = false;
};

// Whatever the file holds: vertices, normals if present, faces if it has any (none for point formats).
Mesh read_geometry(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
// As read_geometry, but the file must hold faces.
Mesh read_mesh(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);
// The file's points (a mesh's vertices), with normals if present.
Cloud read_cloud(const std::string& path, const ReadOptions& options = {}, ReadReport* report = nullptr);

// Atomic: the file appears complete or not at all. A mesh cannot go to a point format (.xyz, .csv, .pcd) without
// losing its faces: that is an error; write to_cloud(mesh) on purpose instead.
void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options = {});
// Points to any format but .stl (which holds only triangles).
void write_cloud(const std::string& path, const Cloud& cloud, const WriteOptions& options = {});

// Per-vertex values written beside the geometry, e.g. a deviation map: viewers (CloudCompare, MeshLab) show the
// scalars as scalar fields and the colours as vertex colours; conform's own reader ignores them with a warning.
struct VertexAttributes {
  // name -> one value per vertex, written as `property float <name>` after x y z (nx ny nz). Names are PLY words
  // (letters, digits, '_'), not one of x y z nx ny nz red green blue.
  std::vector<std::pair<std::string, std::vector<float>>> scalars;
  std::vector<std::array<std::uint8_t, 3>> colors;  // empty, or one RGB per vertex (`property uchar red` ...)
};

// A .ply of the mesh (or of its vertices, when it has no faces) with the attributes, atomic and byte-deterministic
// like write_mesh. Throws conform::Error naming the path when it is not .ply, an attribute does not have one value
// per vertex, or a name is not allowed.
void write_ply_with_attributes(const std::string& path, const Mesh& mesh, const VertexAttributes& attributes,
                               const WriteOptions& options = {});

// Lower-case extension including the dot (".ply"), "" when there is none.
std::string file_extension(const std::string& path);

}  // namespace conform
