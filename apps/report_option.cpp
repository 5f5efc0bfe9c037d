#include "report_option.h"

#include <cstdlib>

#include "conform/core/io.h"
#include "conform/report/html.h"

namespace conform::app {

void add_report_option(CLI::App& command, std::string& path) {
  command
      .add_option("--report", path,
                  "Write a self-contained HTML report (.html): verdict, figures, plots and an interactive 3D view; "
                  "opens from disk without network (docs/report.md)")
      ->check([](const std::string& value) -> std::string {
        const std::string extension = file_extension(value);
        return extension == ".html" || extension == ".htm" ? "" : "the report must be .html, not " + value;
      });
}

std::string report_date() {
  const char* fixed = std::getenv("CONFORM_REPORT_DATE");
  return fixed != nullptr ? std::string(fixed) : html::utc_now_text();
}

void write_report(const std::string& path, const html::Page& page) {
  if (!path.empty()) html::write_html(path, page);
}

}  // namespace conform::app
