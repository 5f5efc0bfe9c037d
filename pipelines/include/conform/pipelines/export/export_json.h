#pragma once
// The JSON and the warnings of `conform export`, and its check of the program name: one source for the CLI and the
// Python binding (conform.export).

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "conform/pipelines/export/export.h"

namespace conform {

// A turn of more than 30 deg between two consecutive frames (a wrist flip, or a corner turned on the spot).
std::vector<std::string> export_warnings(const ExportJobResult& result);

nlohmann::json export_json(const ExportJobOptions& options, const ExportJobResult& result);

// Throws conform::Error when options.program.name is empty and out_path's stem is no valid program name.
void check_export_name(const ExportJobOptions& options);

}  // namespace conform
