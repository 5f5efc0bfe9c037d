// Text helpers of the page: HTML escaping, base64, number formatting, the table cells.

#include <cmath>
#include <cstdio>

#include "report_detail.h"

namespace conform::html {

namespace detail {

std::string escape_html(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string base64(std::string_view bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16 | static_cast<unsigned char>(bytes[i + 1]) << 8 |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += {kAlphabet[v >> 18], kAlphabet[(v >> 12) & 63], kAlphabet[(v >> 6) & 63], kAlphabet[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += {kAlphabet[v >> 18], kAlphabet[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16 | static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += {kAlphabet[v >> 18], kAlphabet[(v >> 12) & 63], kAlphabet[(v >> 6) & 63], '='};
  }
  return out;
}

std::string format_g(double value, int digits) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  return text;
}

}  // namespace detail

const char* to_string(Level level) {
  switch (level) {
    case Level::kOk: return "ok";
    case Level::kCheck: return "check";
    case Level::kFail: return "fail";
  }
  return "fail";
}

Cell number(double value, int decimals, std::string json_pointer) {
  if (!std::isfinite(value)) return Cell(detail::format_g(value, 6), std::move(json_pointer));
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return Cell(text, std::move(json_pointer));
}

Cell number_g(double value, int digits, std::string json_pointer) {
  return Cell(detail::format_g(value, digits), std::move(json_pointer));
}

Cell count(std::size_t value, std::string json_pointer) { return Cell(std::to_string(value), std::move(json_pointer)); }

}  // namespace conform::html
