#pragma once
// Buffered output for the writers, through conform::AtomicFile: the target appears complete on commit() or not at
// all (an exception before commit() leaves neither the target changed nor a temporary behind).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "conform/core/atomic_file.h"

namespace conform::detail {

class OutputFile {
 public:
  explicit OutputFile(const std::string& path);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Append to buffer() freely, then call flush_if_full() now and then (once per record is right).
  std::string& buffer() { return buffer_; }
  void flush_if_full() {
    if (buffer_.size() >= kFlushBytes) flush();
  }
  void commit();

 private:
  static constexpr std::size_t kFlushBytes = std::size_t{1} << 20;
  void flush();

  AtomicFile file_;
  std::string buffer_;
};

// Shortest text that reads back as the same value (std::to_chars: locale-independent and deterministic).
void append_number(std::string& out, double value);
void append_number(std::string& out, float value);
void append_number(std::string& out, std::int64_t value);
// A coordinate as the file's precision: the float nearest to it, or the double itself.
inline void append_coordinate(std::string& out, double value, bool double_precision) {
  if (double_precision) {
    append_number(out, value);
  } else {
    append_number(out, static_cast<float>(value));
  }
}

}  // namespace conform::detail
