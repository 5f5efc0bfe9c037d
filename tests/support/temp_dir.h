#pragma once
// A fresh directory under the system's temp folder, removed with everything in it when the test ends.

#include <string>

namespace conform::test {

class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::string& path() const { return path_; }
  // path()/name
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  // The names of the entries in the directory, sorted (to check that nothing partial was left behind).
  std::string listing() const;

 private:
  std::string path_;
};

// Whole file as bytes; empty string when it does not exist.
std::string read_bytes(const std::string& path);
void write_bytes(const std::string& path, const std::string& bytes);

}  // namespace conform::test
