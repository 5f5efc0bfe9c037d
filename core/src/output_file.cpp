#include "output_file.h"

#include <cerrno>
#include <charconv>
#include <cstring>

#include "conform/core/error.h"

namespace conform::detail {

OutputFile::OutputFile(const std::string& path) : file_(path) {
  stream_ = std::fopen(file_.temp_path().c_str(), "wb");
  if (stream_ == nullptr) {
    throw Error(path + ": cannot open for writing (" + std::string(std::strerror(errno)) + ")");
  }
  buffer_.reserve(kFlushBytes + kFlushBytes / 4);
}

OutputFile::~OutputFile() {
  if (stream_ != nullptr) std::fclose(stream_);
}

void OutputFile::flush() {
  if (!buffer_.empty() && std::fwrite(buffer_.data(), 1, buffer_.size(), stream_) != buffer_.size()) {
    throw Error(file_.path() + ": write failed (" + std::string(std::strerror(errno)) + ")");
  }
  buffer_.clear();
}

void OutputFile::commit() {
  flush();
  std::FILE* stream = stream_;
  stream_ = nullptr;
  // fclose reports the errors of the last buffered write (a full disk shows here, not in fwrite).
  if (std::fclose(stream) != 0) {
    throw Error(file_.path() + ": write failed (" + std::string(std::strerror(errno)) + ")");
  }
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
