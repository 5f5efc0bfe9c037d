#pragma once
// The JSON of `conform align --json`, and the text forms of --method and --init: one source for the CLI and the
// Python binding (conform.align).

#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/align/align.h"

namespace conform {

nlohmann::json align_json(const AlignResult& result);

// --method: "point-to-point", "point-to-plane", "point-to-surface", "plane-to-plane" or "gicp"; "" leaves the
// automatic choice. --init: "none", "pca", "fpfh" or "pairs:FILE". Throw conform::Error for anything else.
void set_align_method(const std::string& method, AlignOptions* options);
void set_align_init(const std::string& init, AlignOptions* options);

}  // namespace conform
