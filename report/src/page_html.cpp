#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <cstdlib>
#include <ctime>

#include "conform/core/atomic_file.h"
#include "conform/core/io.h"
#include "conform/report/html.h"
#include "report_detail.h"

namespace conform::html {
namespace {

using detail::escape_html;

// JSON inside <script type="application/json">: '<' only occurs in strings, where \u003c keeps "</script>" out.
std::string script_json(const std::string& dumped) {
  std::string out;
  out.reserve(dumped.size());
  for (char c : dumped) {
    if (c == '<') {
      out += "\\u003c";
    } else {
      out += c;
    }
  }
  return out;
}

std::string dump(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

bool looks_numeric(const std::string& text) {
  if (text.empty()) return false;
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return end != nullptr && *end == '\0';
}

std::string table_html(const Table& table) {
  std::string out;
  if (!table.title.empty()) out += "<h3>" + escape_html(table.title) + "</h3>";
  out += "<table>";
  if (!table.header.empty()) {
    out += "<tr>";
    for (const std::string& h : table.header) out += "<th>" + escape_html(h) + "</th>";
    out += "</tr>";
  }
  for (const auto& row : table.rows) {
    out += "<tr>";
    for (const Cell& cell : row) {
      out += "<td";
      if (looks_numeric(cell.text)) out += " class=\"num\"";
      if (!cell.json_pointer.empty()) out += " data-json=\"" + escape_html(cell.json_pointer) + "\"";
      out += ">" + escape_html(cell.text) + "</td>";
    }
    out += "</tr>";
  }
  return out + "</table>";
}

std::string value_text(const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : dump(v); }

std::string header_html(const Page& page) {
  const std::string title = page.title.empty() ? "conform " + page.job : page.title;
  std::string out = "<header><h1>" + escape_html(title) + "</h1>";
  out += "<p class=\"verdict " + std::string(to_string(page.verdict.level)) + "\" id=\"conform-verdict\">" +
         escape_html(page.verdict.text) + "</p>";
  out += "<table class=\"meta\"><tr><td>job</td><td>" + escape_html(page.job) + "</td></tr>";
  for (const Input& in : page.inputs) {
    out += "<tr><td>input</td><td>" + escape_html(in.name) + (in.size.empty() ? "" : " (" + escape_html(in.size) + ")") +
           "</td></tr>";
  }
  if (!page.date.empty()) out += "<tr><td>date</td><td>" + escape_html(page.date) + "</td></tr>";
  out += "<tr><td>conform</td><td>" + escape_html(page.version.empty() ? conform_version() : page.version) +
         "</td></tr></table>";
  if (!page.warnings.empty()) {
    out += "<ul class=\"warnings\" id=\"conform-warnings\">";
    for (const std::string& w : page.warnings) out += "<li>" + escape_html(w) + "</li>";
    out += "</ul>";
  }
  return out + "</header>";
}

std::string css(const Rgb& c) {
  char text[16];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c[0], c[1], c[2]);
  return text;
}

// The layer's colour beside its checkbox: its one colour, or (coloured per point) the colour bar's scale when the
// scene has one, else its first colours.
std::string swatch(const SceneObject& s, const std::optional<ColourBar>& bar) {
  std::string background = css(s.colour);
  if (!s.colours.empty()) {
    std::vector<Rgb> samples;
    if (bar && !bar->stops.empty()) {
      for (std::size_t k = 0; k < 5; ++k) samples.push_back(bar->stops[k * (bar->stops.size() - 1) / 4].second);
    } else {
      for (std::size_t k = 0; k < 3; ++k) samples.push_back(s.colours[k * (s.colours.size() - 1) / 2]);
    }
    background = "linear-gradient(90deg";
    for (const Rgb& c : samples) background += "," + css(c);
    background += ")";
  }
  char opacity[32] = "";
  if (s.kind == ObjectKind::kMesh && s.opacity < 1.0) std::snprintf(opacity, sizeof opacity, ";opacity:%.2f", s.opacity);
  return "<span class=\"swatch\" style=\"background:" + background + opacity + "\"></span>";
}

std::string view_html(const Scene& scene, const std::vector<SceneObject>& shown) {
  const Eigen::Vector3d o = scene.origin();
  std::string out = "<section id=\"view-section\"><h2>3D view</h2><div class=\"viewer\">";
  out += "<div class=\"view\" id=\"conform-view\"><div class=\"readout\" id=\"conform-readout\"></div></div>"
         "<div class=\"side\">";
  out += "<button id=\"conform-reset\" type=\"button\">Reset view</button><h3>Layers</h3>";
  for (std::size_t i = 0; i < shown.size(); ++i) {
    const SceneObject& s = shown[i];
    out += "<label><input type=\"checkbox\" data-layer=\"" + std::to_string(i) + "\"" + (s.visible ? " checked" : "") +
           "> " + swatch(s, scene.colour_bar()) + escape_html(s.name) + "</label>";
  }
  if (!scene.callouts().empty()) {
    out += "<label><input type=\"checkbox\" id=\"conform-callouts\" checked> <span class=\"swatch\" "
           "style=\"background:#fff;border-color:#111\"></span>callouts</label>";
  }
  if (scene.colour_bar()) out += detail::colour_bar_svg(*scene.colour_bar());
  out += "</div></div><p class=\"note\">Drag: orbit; wheel: zoom; right drag or shift + drag: pan; click a point: its "
         "coordinates (and value) in the box at the lower left. Coordinates in mm, "
         "relative to the origin (" +
         detail::format_g(o.x(), 10) + ", " + detail::format_g(o.y(), 10) + ", " + detail::format_g(o.z(), 10) +
         ") mm of the job's frame.</p>";
  for (const std::string& note : scene.notes(shown)) out += "<p class=\"note\">Thinned for the page: " + escape_html(note) + "</p>";
  return out + "</section>";
}

std::string section_html(const Section& s) {
  std::string out = "<section><h2>" + escape_html(s.title) + "</h2>";
  for (const std::string& p : s.paragraphs) out += "<p>" + escape_html(p) + "</p>";
  for (const Table& t : s.tables) out += table_html(t);
  for (const Plot& p : s.plots) out += detail::plot_svg(p);
  return out + "</section>";
}

}  // namespace

const char* conform_version() { return CONFORM_VERSION; }

std::string utc_now_text() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
  return text;
}

std::string report_date() {
  const char* fixed = std::getenv("CONFORM_REPORT_DATE");
  return fixed != nullptr ? std::string(fixed) : utc_now_text();
}

bool is_report_path(const std::string& path) {
  const std::string extension = file_extension(path);
  return extension == ".html" || extension == ".htm";
}

std::string render_html(const Page& page) {
  const std::string title = page.title.empty() ? "conform " + page.job : page.title;
  std::string out =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; script-src 'unsafe-inline'; "
      "style-src 'unsafe-inline'; img-src data:\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
      escape_html(title) + "</title>\n<style>" + detail::page_css() + "</style></head>\n";
  out += "<body data-job=\"" + escape_html(page.job) + "\" data-verdict=\"" + to_string(page.verdict.level) + "\">\n";
  out += header_html(page) + "\n";
  std::vector<SceneObject> shown;
  if (!page.scene.empty()) {
    shown = page.scene.thinned();
    out += view_html(page.scene, shown) + "\n";
  }
  for (const Section& s : page.sections) out += section_html(s) + "\n";
  if (!page.options.empty()) {
    Table options{"", {"option", "value"}, {}};
    for (const auto& [key, value] : page.options.items()) options.rows.push_back({key, value_text(value)});
    out += "<section><h2>Options</h2>" + table_html(options) + "</section>\n";
  }
  out += "<section><h2>Result (JSON)</h2><details><summary>The job's --json output, as embedded in this page"
         "</summary><pre id=\"conform-json-text\"></pre></details></section>\n";
  out += "<script type=\"application/json\" id=\"conform-result\">" + script_json(dump(page.result)) + "</script>\n";
  if (!page.scene.empty()) {
    out += "<script type=\"application/json\" id=\"conform-scene\">" +
           script_json(detail::scene_json(page.scene, shown)) + "</script>\n";
    out += "<script>" + detail::three_min_js() + "</script>\n<script>" + detail::orbit_controls_js() + "</script>\n";
  }
  out += "<script>" + std::string(detail::viewer_js()) + "</script>\n</body></html>\n";
  return out;
}

void write_html(const std::string& path, const Page& page) { write_file_atomically(path, render_html(page)); }

}  // namespace conform::html
