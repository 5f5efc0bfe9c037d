#include "report_option.h"

#include "conform/report/html.h"

namespace conform::app {

void add_report_option(CLI::App& command, std::string& path) {
  command
      .add_option("--report", path,
                  "Write a self-contained HTML report (.html): verdict, figures, plots and an interactive 3D view; "
                  "opens from disk without network (docs/report.md)")
      ->check([](const std::string& value) -> std::string {
        return html::is_report_path(value) ? "" : "the report must be .html, not " + value;
      });
}

void write_report(const std::string& path, const html::Page& page) {
  if (!path.empty()) html::write_html(path, page);
}

}  // namespace conform::app
