#pragma once
// A whole input file in memory. The readers parse from memory because it lets them check a header's counts against
// the real size before allocating, and because one read() of the file is much faster than stream extraction.

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

namespace conform::detail {

class FileBytes {
 public:
  FileBytes(std::unique_ptr<char[]> data, std::size_t size) : data_(std::move(data)), size_(size) {}
  const char* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  std::string_view view() const { return {data_.get(), size_}; }

 private:
  std::unique_ptr<char[]> data_;
  std::size_t size_;
};

// conform::read_input_file() (input_file.h) with the bytes kept as they are: the same checks, the same messages.
FileBytes read_file_bytes(const std::string& path);

}  // namespace conform::detail
