#include "text_scanner.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>

namespace conform::detail {

bool LineScanner::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const std::size_t end = text_.find('\n', pos_);
  const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
  line = text_.substr(pos_, stop - pos_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = end == std::string_view::npos ? text_.size() : end + 1;
  ++next_number_;
  return true;
}

bool TokenStream::next(std::string_view& token) {
  std::size_t begin = 0;
  while (begin < rest_.size() && is_space(rest_[begin])) {
    if (rest_[begin] == '\n') ++line_;
    ++begin;
  }
  if (begin == rest_.size()) {
    rest_ = {};
    return false;
  }
  std::size_t end = begin;
  while (end < rest_.size() && !is_space(rest_[end])) ++end;
  token = rest_.substr(begin, end - begin);
  rest_.remove_prefix(end);
  return true;
}

void TokenStream::skip_line() {
  const std::size_t end = rest_.find('\n');
  rest_.remove_prefix(end == std::string_view::npos ? rest_.size() : end);
}

bool next_token(std::string_view& rest, std::string_view& token) {
  std::size_t begin = 0;
  while (begin < rest.size() && is_space(rest[begin])) ++begin;
  if (begin == rest.size()) {
    rest = {};
    return false;
  }
  std::size_t end = begin;
  while (end < rest.size() && !is_space(rest[end])) ++end;
  token = rest.substr(begin, end - begin);
  rest.remove_prefix(end);
  return true;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

bool starts_with(std::string_view text, std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; }

namespace {
char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

template <typename T>
std::from_chars_result parse_whole(std::string_view token, T& value) {
  // from_chars rejects the '+' that printf-style writers put in front of positive numbers.
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
  std::from_chars_result result = std::from_chars(token.data(), token.data() + token.size(), value);
  if (result.ec == std::errc() && result.ptr != token.data() + token.size()) result.ec = std::errc::invalid_argument;
  return result;
}
}  // namespace

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() &&
         std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) { return lower(x) == lower(y); });
}

std::string to_lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = lower(c);
  return out;
}

bool parse_number(std::string_view token, double& value) { return parse_whole(token, value).ec == std::errc(); }
bool parse_number(std::string_view token, float& value) { return parse_whole(token, value).ec == std::errc(); }
bool parse_number(std::string_view token, std::int64_t& value) { return parse_whole(token, value).ec == std::errc(); }
bool parse_number(std::string_view token, std::uint64_t& value) { return parse_whole(token, value).ec == std::errc(); }

std::string describe_bad_number(std::string_view token, bool integer) {
  constexpr std::size_t kMaxShown = 40;
  std::string shown = "'" + std::string(token.substr(0, kMaxShown)) + (token.size() > kMaxShown ? "...'" : "'");
  double as_double = 0.0;
  const std::errc ec = parse_whole(token, as_double).ec;
  // A token that is a fine double failed as something narrower: a float or integer range, or a fraction.
  if (ec == std::errc::result_out_of_range) return shown + " is out of range";
  if (ec != std::errc()) return shown + " is not a number";
  if (integer && !(as_double == std::trunc(as_double))) {
    return shown + " is not an integer";
  }
  return shown + " is out of range";
}

}  // namespace conform::detail
