#include "output_file.h"

#include <charconv>

namespace conform::detail {

OutputFile::OutputFile(const std::string& path) : file_(path) { buffer_.reserve(kFlushBytes + kFlushBytes / 4); }

void OutputFile::flush() {
  file_.write(buffer_.data(), buffer_.size());
  buffer_.clear();
}

void OutputFile::commit() {
  flush();
  file_.commit();
}

namespace {
template <typename T>
void append_with_to_chars(std::string& out, T value) {
  char text[64];
  const std::to_chars_result result = std::to_chars(text, text + sizeof(text), value);
  out.append(text, result.ptr);
}
}  // namespace

void append_number(std::string& out, double value) { append_with_to_chars(out, value); }
void append_number(std::string& out, float value) { append_with_to_chars(out, value); }
void append_number(std::string& out, std::int64_t value) { append_with_to_chars(out, value); }

}  // namespace conform::detail
