#include "terminal.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include <unistd.h>

namespace conform::app {

namespace {
struct ProgressState {
  std::string stage;
  std::chrono::steady_clock::time_point last_draw{};
  bool tty = ::isatty(STDERR_FILENO) != 0;
};
}  // namespace

ProgressFn stderr_progress(bool quiet) {
  if (quiet) return {};
  auto state = std::make_shared<ProgressState>();
  return [state](std::string_view stage, double fraction) {
    const auto now = std::chrono::steady_clock::now();
    if (stage != state->stage) {
      if (state->tty && !state->stage.empty()) std::cerr << '\n';
      state->stage = std::string(stage);
      state->last_draw = now;
      std::cerr << "conform: " << stage << (state->tty ? " ..." : " ...\n") << std::flush;
      return;
    }
    if (!state->tty) return;
    if (fraction < 1.0 && now - state->last_draw < std::chrono::milliseconds(500)) return;
    state->last_draw = now;
    std::cerr << "\rconform: " << stage << " " << static_cast<int>(100.0 * fraction) << "%"
              << (fraction >= 1.0 ? "\n" : "") << std::flush;
    if (fraction >= 1.0) state->stage.clear();
  };
}

namespace {

// The length of the valid UTF-8 sequence starting at text[i] (RFC 3629: no overlong forms, no surrogates, at most
// U+10FFFF), 0 when there is none.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i);
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xbf;  // the allowed range of the second byte
  if (c >= 0xc2 && c <= 0xdf) {
    n = 2;
  } else if (c >= 0xe0 && c <= 0xef) {
    n = 3;
    if (c == 0xe0) lo = 0xa0;
    if (c == 0xed) hi = 0x9f;
  } else if (c >= 0xf0 && c <= 0xf4) {
    n = 4;
    if (c == 0xf0) lo = 0x90;
    if (c == 0xf4) hi = 0x8f;
  } else {
    return 0;
  }
  if (text.size() - i < n || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xbf) return 0;
  }
  return n;
}

}  // namespace

std::string printable(std::string_view text) {
  static const char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += text[i++];
      continue;
    }
    const std::size_t n = c >= 0x80 ? utf8_length(text, i) : 0;
    if (n > 0 || c == '\n' || c == '\t') {
      out.append(text.substr(i, std::max<std::size_t>(n, 1)));
      i += std::max<std::size_t>(n, 1);
      continue;
    }
    out += "\\x";
    out += kHex[c >> 4];
    out += kHex[c & 15];
    ++i;
  }
  return out;
}

void warn(std::string_view message) { std::cerr << "conform: warning: " << printable(message) << '\n'; }

void warn_all(const std::vector<std::string>& messages) {
  for (const std::string& m : messages) warn(m);
}

// error_handler_t::replace: a file name or id that is not UTF-8 (any byte string is a valid Linux file name) becomes
// U+FFFD in the JSON instead of a type_error 316 after the job's work is done.
void print_json(const nlohmann::json& object) {
  std::cout << object.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << std::endl;
}

}  // namespace conform::app
