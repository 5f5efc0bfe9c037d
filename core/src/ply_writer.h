#pragma once
// The pieces of conform's PLY output, shared by write_ply (ply_writer.cpp) and write_ply_with_attributes
// (ply_attributes_writer.cpp), so that both write the same header lines and the same vertex and face records.

#include <cstddef>
#include <string>

#include "conform/core/io.h"
#include "conform/core/mesh.h"
#include "output_file.h"

namespace conform::detail {

// "ply", the format line and conform's comment.
std::string ply_header_start(const WriteOptions& options);
// "element vertex N" and the x y z (nx ny nz) properties.
std::string ply_vertex_element(const Mesh& mesh, const WriteOptions& options);
// "element face N" and its index list; "" for a mesh without faces.
std::string ply_face_element(const Mesh& mesh);

// Vertex i's position (and normal) as binary or as ascii text (space-separated, no line end).
void append_ply_vertex(std::string& out, const Mesh& mesh, std::size_t i, const WriteOptions& options);
// Every face record after the vertices.
void write_ply_faces(OutputFile& out, const Mesh& mesh, const WriteOptions& options);

}  // namespace conform::detail
