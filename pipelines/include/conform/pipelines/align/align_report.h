#pragma once
// The HTML report of `conform align --report` (docs/report.md): the verdict (trust yes / check / no and why), the
// scan at the pose found coloured by its deviation from the semi-transparent reference, the pose T_ref_scan, its
// predicted standard deviations, the motions the scan does not constrain, the fit figures and the histogram.

#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/align/align.h"
#include "conform/report/page.h"

namespace conform {

// `result` from run_align with options.keep_geometry; `json` is align_json of it. The deviations are measured here
// (evaluation/deviation.h) for the scan points shown (at most the page's point limit, an even stride).
html::Page align_report(const AlignOptions& options, const AlignResult& result, const nlohmann::json& json,
                        const std::string& date);

}  // namespace conform
