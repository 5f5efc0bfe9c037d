#include "output_paths.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include "conform/core/error.h"

namespace conform::detail {

namespace fs = std::filesystem;

std::string errno_text() { return std::strerror(errno); }

std::string resolve_symlinks(const std::string& path) {
  fs::path p = path;
  for (int links = 0; links <= 40; ++links) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) return p.string();
    std::error_code error;
    const fs::path to = fs::read_symlink(p, error);
    if (error) throw Error(path + ": cannot read the symbolic link (" + error.message() + ")");
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  throw Error(path + ": too many levels of symbolic links");
}

std::string directory_of(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

std::string random_hex(std::size_t length) {
  std::string bytes((length + 1) / 2, '\0');
  std::size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::getrandom(bytes.data() + got, bytes.size() - got, 0);
    if (n > 0) {
      got += static_cast<std::size_t>(n);
    } else if (n < 0 && errno != EINTR) {
      std::ifstream urandom("/dev/urandom", std::ios::binary);
      if (!urandom.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
        throw Error("no source of random numbers for a temporary file name (getrandom and /dev/urandom failed)");
      }
      got = bytes.size();
    }
  }
  static const char digits[] = "0123456789abcdef";
  std::string out;
  for (char c : bytes) {
    const auto byte = static_cast<std::uint8_t>(c);
    out += digits[byte >> 4];
    out += digits[byte & 15];
  }
  out.resize(length);
  return out;
}

std::string sibling_name(const std::string& target, const char* tag) {
  const fs::path p = target;
  std::string name = p.filename().string();
  constexpr std::size_t kMaxBase = 200;  // NAME_MAX is 255: room for the tag and 16 digits
  if (name.size() > kMaxBase) name.resize(kMaxBase);
  return (p.parent_path() / (name + tag + random_hex(16))).string();
}

void fsync_directory(const std::string& directory) {
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace conform::detail
