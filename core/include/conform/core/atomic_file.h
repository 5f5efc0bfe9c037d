#pragma once
// Output that appears whole or not at all: write to a temporary file beside the target, rename it over the target
// on commit(). Destroyed without commit (an exception on the way), the temporary is removed and the target untouched.

#include <string>

namespace conform {

class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& path() const { return path_; }
  // Where to write; in the target's directory so that the rename is atomic.
  const std::string& temp_path() const { return temp_path_; }
  // Renames the temporary over the target. Throws conform::Error if the rename fails.
  void commit();

 private:
  std::string path_;
  std::string temp_path_;
  bool committed_ = false;
};

// Writes `contents` to `path` atomically. Throws conform::Error naming the path when it cannot.
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace conform
