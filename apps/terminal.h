#pragma once
// Everything conform says to a person goes through here: progress and warnings on stderr, JSON on stdout.

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "conform/core/progress.h"

namespace conform::app {

// Progress on stderr: one line per stage, and percentages at most twice a second when stderr is a terminal.
ProgressFn stderr_progress(bool quiet);

void warn(std::string_view message);
void warn_all(const std::vector<std::string>& messages);

// One JSON object on stdout, nothing else (DESIGN.md: --json output).
void print_json(const nlohmann::json& object);

}  // namespace conform::app
