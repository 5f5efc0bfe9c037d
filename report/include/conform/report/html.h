#pragma once
// A report Page as one self-contained HTML file (docs/report.md): inline CSS, the tables, the plots as inline SVG,
// three.js (Debian's libjs-three, compiled in) and the scene's geometry as base64 float32 arrays. A
// Content-Security-Policy forbids every network fetch; the page works opened from disk on a PC without internet.

#include <string>

#include "conform/report/page.h"

namespace conform::html {

// The whole page. Same Page, same bytes.
std::string render_html(const Page& page);

// render_html written to `path` whole or not at all (core/atomic_file.h; inside a command's OutputSet it appears
// with the command's other outputs). Throws conform::Error naming the path when it cannot be written.
void write_html(const std::string& path, const Page& page);

// "0.1.0": the version this build of conform reports.
const char* conform_version();
// The current time, UTC, "2026-11-23 17:40 UTC" (for Page::date).
std::string utc_now_text();
// The date a job's page shows (the CLI's --report, Python's report=): utc_now_text(), or the value of the environment
// variable CONFORM_REPORT_DATE when it is set (same input, same bytes, for tests and reproducible builds).
std::string report_date();
// Whether `path` names a report: it ends in .html or .htm (any case).
bool is_report_path(const std::string& path);

}  // namespace conform::html
