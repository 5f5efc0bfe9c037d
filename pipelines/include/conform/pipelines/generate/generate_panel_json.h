#pragma once
// `conform generate plate` and `generate nosecone`: the opening's text form and the JSON, one source for the CLI and
// the Python binding (conform.generate_plate, conform.generate_nosecone).

#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/generate/generate_panel.h"

namespace conform {

// --opening: "ellipse" or "rectangle"; conform::Error naming the flag otherwise.
PlateOpening plate_opening(const std::string& text);

nlohmann::json generate_panel_json(const GeneratePanelResult& result);

}  // namespace conform
