#pragma once
// The per-format readers and writers behind conform/core/io.h. io.cpp picks one by extension, applies the
// NonFinitePolicy and checks what the caller asked for (faces, no faces); the functions here only translate.
// Every reader returns what the file holds with face indices already checked against the vertex count, and adds
// its warnings (prefixed with the path) to `report`.

#include <string>

#include "conform/core/cloud.h"
#include "conform/core/io.h"
#include "conform/core/mesh.h"

namespace conform::detail {

Mesh read_ply(const std::string& path, ReadReport& report);
void write_ply(const std::string& path, const Mesh& mesh, const WriteOptions& options);

Mesh read_stl(const std::string& path, ReadReport& report);
void write_stl(const std::string& path, const Mesh& mesh, const WriteOptions& options);

Mesh read_obj(const std::string& path, ReadReport& report);
void write_obj(const std::string& path, const Mesh& mesh, const WriteOptions& options);

// .xyz .txt .asc .csv
Mesh read_point_list(const std::string& path, ReadReport& report);
void write_point_list(const std::string& path, const Mesh& mesh, const WriteOptions& options);

Mesh read_pcd(const std::string& path, ReadReport& report);
void write_pcd(const std::string& path, const Cloud& cloud, const WriteOptions& options);

}  // namespace conform::detail
