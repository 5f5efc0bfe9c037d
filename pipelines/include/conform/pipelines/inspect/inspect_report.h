#pragma once
// The HTML report of `conform inspect --report` (docs/report.md): the verdict (the tolerances', or whether the job
// gave figures), the scan coloured by its deviation from its face over the semi-transparent CAD, a table of the faces
// (deviation, form, the fitted feature against nominal, pass/fail), the job's JSON.

#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/inspect/inspect.h"
#include "conform/report/page.h"

namespace conform {

// `result` from run_inspect with options.keep_geometry; `json` is inspect_json of it. `date` as the page shows it.
html::Page inspect_report(const InspectOptions& options, const InspectResult& result, const nlohmann::json& json,
                          const std::string& date);

}  // namespace conform
