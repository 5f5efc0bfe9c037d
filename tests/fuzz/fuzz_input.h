#pragma once
// What every harness shares: libFuzzer hands over bytes, conform's readers take a path (the file checks are part of
// what is fuzzed), so each input is written to one scratch file, on /dev/shm when there is one.
// A reader may throw conform::Error (bad input, the expected outcome); anything else escapes and libFuzzer reports
// it as a crash, like a sanitizer finding.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <unistd.h>

namespace conform::fuzz {

class ScratchFile {
 public:
  explicit ScratchFile(const char* extension) {
    std::string dir = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    dir += "/conform-fuzz-XXXXXX";
    if (::mkdtemp(dir.data()) == nullptr) std::abort();
    dir_ = dir;
    path_ = dir + "/input" + extension;
  }
  ~ScratchFile() {
    std::remove(path_.c_str());
    ::rmdir(dir_.c_str());
  }
  // Writes the input and returns the path to read.
  const std::string& write(const std::uint8_t* data, std::size_t size) {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (f == nullptr || std::fwrite(data, 1, size, f) != size || std::fclose(f) != 0) std::abort();
    return path_;
  }

 private:
  std::string dir_;
  std::string path_;
};

}  // namespace conform::fuzz

// One harness per reader: CONFORM_FUZZ_READER(".ply", read_geometry(path, options)) defines the libFuzzer entry
// point that writes the input to a scratch file with that extension and calls the expression on `path`.
#define CONFORM_FUZZ_READER(extension, call)                                         \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    static conform::fuzz::ScratchFile scratch(extension);                            \
    const std::string& path = scratch.write(data, size);                             \
    try {                                                                            \
      (void)(call);                                                                  \
    } catch (const conform::Error&) {                                                \
    }                                                                                \
    return 0;                                                                        \
  }
