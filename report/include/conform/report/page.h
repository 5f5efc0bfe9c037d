#pragma once
// One report page (docs/report.md): a header (job, inputs, options, date, version, verdict, warnings), sections of
// tables and plots, the 3D view (scene.h) and the job's full JSON, embedded so that a reader (or a test) can check
// every number on the page against it. render_html (html.h) turns it into one self-contained HTML file.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "conform/report/plot.h"
#include "conform/report/scene.h"

namespace conform::html {

enum class Level { kOk, kCheck, kFail };
const char* to_string(Level level);  // "ok", "check", "fail"

struct Verdict {
  Level level = Level::kFail;
  std::string text;  // one line: "within tolerance: 99.2 % of the points inside +-0.1 mm"
};

struct Input {
  std::string name;  // the path as given
  std::string size;  // "120000 points", "2400 triangles", "3.2 MB"
};

// A table cell: its text, and optionally the JSON pointer (RFC 6901, "/stats/rms_mm") of the value it shows in the
// page's JSON, so that the page can be checked against it (written as data-json on the cell).
struct Cell {
  Cell() = default;
  Cell(std::string text_) : text(std::move(text_)) {}  // NOLINT: plain text converts
  Cell(const char* text_) : text(text_) {}             // NOLINT
  Cell(std::string text_, std::string json_pointer_) : text(std::move(text_)), json_pointer(std::move(json_pointer_)) {}
  std::string text;
  std::string json_pointer;
};

// `value` with `decimals` decimals ("%.*f"), tied to `json_pointer` (may be empty).
Cell number(double value, int decimals, std::string json_pointer = {});
// `value` in "%.*g" with `digits` significant digits.
Cell number_g(double value, int digits, std::string json_pointer = {});
// A count, as an integer.
Cell count(std::size_t value, std::string json_pointer = {});

struct Table {
  std::string title;
  std::vector<std::string> header;  // may be empty (a key-value table)
  std::vector<std::vector<Cell>> rows;
};

struct Section {
  std::string title;
  std::vector<std::string> paragraphs;  // plain text, escaped
  std::vector<Table> tables;
  std::vector<Plot> plots;
};

struct Page {
  std::string job;    // "compare"
  std::string title;  // the page's heading; empty: "conform <job>"
  std::vector<Input> inputs;
  nlohmann::json options = nlohmann::json::object();  // shown as a table of key = value
  std::string date;     // as the caller gives it (e.g. utc_now_text()); empty: not shown
  std::string version;  // empty: this build's conform_version()
  Verdict verdict;
  std::vector<std::string> warnings;
  std::vector<Section> sections;  // after the 3D view
  Scene scene;                    // no objects: no 3D view
  nlohmann::json result = nlohmann::json::object();  // the job's JSON (--json), embedded as is
};

}  // namespace conform::html
