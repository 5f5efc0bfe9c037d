#pragma once
// The HTML report of `conform compare --report` (docs/report.md): the verdict (in or out of tolerance), the scan
// coloured by deviation over the semi-transparent reference, the statistics and the histogram, the job's JSON.

#include <nlohmann/json.hpp>

#include "conform/pipelines/compare/compare.h"
#include "conform/report/page.h"

namespace conform {

// `result` from run_compare with options.keep_geometry; `json` is compare_json of it (embedded, and what the
// page's figures are tied to). `date` as the page shows it (empty: none).
html::Page compare_report(const CompareOptions& options, const CompareResult& result, const nlohmann::json& json,
                          const std::string& date);

}  // namespace conform
