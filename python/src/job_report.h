#pragma once
// `report=` on the jobs that have the CLI's --report (docs/report.md): the same page, built by the job's
// pipelines/<job>_report.h from its result, dated as the CLI dates it (CONFORM_REPORT_DATE fixes the date). Written
// also when the job did not succeed (the page's verdict says why), never when it raises conform.Error.

#include <string>

#include <pybind11/pybind11.h>

#include "conform/report/page.h"
#include "inputs.h"

namespace conform::python {

// The report's path ("" for None); a path not ending in .html or .htm raises conform.Error before any work.
std::string report_path_of(const py::handle& value);

// Writes `page` to `path` whole or not at all; nothing when `path` is empty.
void write_report(const std::string& path, html::Page page);

}  // namespace conform::python
