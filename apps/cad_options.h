#pragma once
// The CAD options every command that reads a reference surface shares (align, compare, sicp --surface, tube-joint,
// fit-cylinder, info), and how a CAD read is reported: one line of text, one JSON object per file.

#include <cstdio>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "conform/core/cad.h"
#include "conform/pipelines/common/cad_json.h"

namespace conform::app {

// --cad-deflection (mm), --cad-angle-deg, the reader's limits (--cad-timeout s, --cad-memory-mib,
// --cad-max-triangles) and --cad-save-mesh (declare cad.save_mesh_path as an output). The command sets cad.progress
// (stages "read CAD", "tessellate CAD").
void add_cad_options(CLI::App& command, CadReadOptions& cad);

// "cad           part.step: STEP in millimetre (x1 to mm), 1 bodies (1 solids), 12 faces -> 468 triangles ..."
void print_cad_text(const std::vector<CadReport>& reports, std::FILE* out = stdout);


}  // namespace conform::app
