#pragma once
// Splitting text into numbered lines and tokens, and parsing numbers, for the ascii readers (PLY, STL, OBJ, point
// lists, transforms). Numbers go through std::from_chars: it ignores the C locale (a German locale must not turn
// "1.5" into 1) and is several times faster than strtod or stream extraction.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace conform::detail {

// The lines of a text with their 1-based numbers. Lines end with "\n" or "\r\n"; the ending is not returned.
class LineScanner {
 public:
  explicit LineScanner(std::string_view text, std::size_t first_line_number = 1)
      : text_(text), next_number_(first_line_number) {}

  // The next line; false at the end of the text.
  bool next(std::string_view& line);
  // The number of the line last returned by next().
  std::size_t line_number() const { return next_number_ - 1; }
  // Where the unread rest of the text starts.
  std::size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t next_number_;
};

// Whitespace-separated tokens across lines, for formats whose values need not keep to lines (ascii PLY and STL).
class TokenStream {
 public:
  explicit TokenStream(std::string_view text, std::size_t first_line_number = 1)
      : rest_(text), line_(first_line_number) {}

  // The next token; false at the end of the text.
  bool next(std::string_view& token);
  // Skips what is left of the current line (an STL solid's name, say).
  void skip_line();
  // The line of the token last returned (or where the text ended).
  std::size_t line_number() const { return line_; }
  std::size_t bytes_left() const { return rest_.size(); }

 private:
  std::string_view rest_;
  std::size_t line_;
};

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

// The next whitespace-separated token of `rest` (which is advanced past it); false when only whitespace is left.
bool next_token(std::string_view& rest, std::string_view& token);

std::string_view trim(std::string_view text);
bool starts_with(std::string_view text, std::string_view prefix);
bool iequals(std::string_view a, std::string_view b);
std::string to_lower(std::string_view text);

// A whole token as a number; false if any of it is not part of the number. A leading '+' is accepted, and so are
// "nan" and "inf" (whether those are allowed is the NonFinitePolicy's business, not the tokenizer's).
bool parse_number(std::string_view token, double& value);
bool parse_number(std::string_view token, float& value);
bool parse_number(std::string_view token, std::int64_t& value);
bool parse_number(std::string_view token, std::uint64_t& value);

// Why parse_number() refused `token`: "'tok' is not a number", "... is out of range" or "... is not an integer"
// (`integer`: an integer was wanted); the token quoted and shortened, for error messages.
std::string describe_bad_number(std::string_view token, bool integer = false);

}  // namespace conform::detail
