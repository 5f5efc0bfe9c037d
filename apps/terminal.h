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

// `text` with every byte that is not printable ASCII or part of valid UTF-8 (bytes of a non-UTF-8 file name, control
// characters but newline and tab) written as \xNN, so that a message cannot garble or drive the terminal.
std::string printable(std::string_view text);

void warn(std::string_view message);
void warn_all(const std::vector<std::string>& messages);

// One JSON object on stdout, nothing else (DESIGN.md: --json output). Strings that are not valid UTF-8 have their
// bad bytes replaced by U+FFFD. Every command prints its JSON through here.
void print_json(const nlohmann::json& object);

}  // namespace conform::app
