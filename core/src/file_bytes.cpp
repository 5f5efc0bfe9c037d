#include "file_bytes.h"

#include <cerrno>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "conform/core/error.h"

namespace conform::detail {

namespace {

std::string system_reason() { return std::strerror(errno); }

// Closes the descriptor on every path out, exceptions included.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

FileBytes read_file_bytes(const std::string& path) {
  FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) throw Error(path + ": cannot open (" + system_reason() + ")");
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0) throw Error(path + ": cannot read (" + system_reason() + ")");
  if (S_ISDIR(info.st_mode)) throw Error(path + ": is a directory, not a file");
  if (!S_ISREG(info.st_mode)) throw Error(path + ": is not a regular file");
  const auto size = static_cast<std::size_t>(info.st_size);
  if (size == 0) throw Error(path + ": is empty");

  // new char[] rather than a vector: no zero-filling of what read() overwrites anyway.
  std::unique_ptr<char[]> data(new char[size]);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t got = ::read(fd.get(), data.get() + done, size - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw Error(path + ": cannot read (" + system_reason() + ")");
    if (got == 0) {
      throw Error(path + ": file shrank while being read (" + std::to_string(done) + " of " + std::to_string(size) +
                  " bytes)");
    }
    done += static_cast<std::size_t>(got);
  }
  return FileBytes(std::move(data), size);
}

}  // namespace conform::detail
