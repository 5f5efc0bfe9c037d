#pragma once
// `--report FILE.html`, shared by every job (docs/report.md): the option, its check, and the write. The page is
// built by the job's pipelines/<job>_report.h from its Result and JSON; the command only writes it, through the
// command's OutputSet (declare it in declare_files), so it appears with the other outputs, also when the job exits 1
// (the verdict on the page says why), never when it exits 2.

#include <string>

#include <CLI/CLI.hpp>

#include "conform/report/html.h"
#include "conform/report/page.h"

namespace conform::app {

// Adds --report to `command`, bound to `path`. A path not ending in .html or .htm is refused when parsed (exit 2).
void add_report_option(CLI::App& command, std::string& path);

// The date a page shows (report/html.h): now, UTC, or CONFORM_REPORT_DATE.
using html::report_date;

// Writes `page` to `path` (nothing when `path` is empty). Throws conform::Error naming the path when it cannot.
void write_report(const std::string& path, const html::Page& page);

}  // namespace conform::app
