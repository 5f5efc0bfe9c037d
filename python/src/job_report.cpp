#include "job_report.h"

#include "conform/core/error.h"
#include "conform/report/html.h"

namespace conform::python {

std::string report_path_of(const py::handle& value) {
  const std::string path = path_of(value);
  if (!path.empty() && !html::is_report_path(path)) throw Error("report: the report must be .html, not " + path);
  return path;
}

void write_report(const std::string& path, html::Page page) {
  if (path.empty()) return;
  page.date = html::report_date();
  html::write_html(path, page);
}

}  // namespace conform::python
