#include "file_bytes.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "conform/core/error.h"
#include "conform/core/input_file.h"

namespace conform {
namespace detail {

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

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  return "not a regular file";
}

}  // namespace

FileBytes read_file_bytes(const std::string& path) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer before fstat() can tell what it is. It changes nothing for
  // a regular file, the only kind read.
  FileDescriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY));
  if (fd.get() < 0) throw Error(path + ": cannot open (" + system_reason() + ")");
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0) throw Error(path + ": cannot read (" + system_reason() + ")");
  if (!S_ISREG(info.st_mode)) throw Error(path + ": is " + kind_of(info.st_mode) + ", not a regular file");
  const auto size = static_cast<std::uint64_t>(info.st_size);
  if (size == 0) throw Error(path + ": is empty");
  if (size > kMaxInputFileBytes) {
    throw Error(path + ": is " + std::to_string(size) + " bytes, more than conform reads (" +
                std::to_string(kMaxInputFileBytes) + " bytes)");
  }
  const auto bytes = static_cast<std::size_t>(size);

  // new char[] rather than a vector: no zero-filling of what read() overwrites anyway.
  std::unique_ptr<char[]> data(new char[bytes]);
  std::size_t done = 0;
  while (done < bytes) {
    const ssize_t got = ::read(fd.get(), data.get() + done, bytes - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw Error(path + ": cannot read (" + system_reason() + ")");
    if (got == 0) {
      throw Error(path + ": file shrank while being read (" + std::to_string(done) + " of " + std::to_string(bytes) +
                  " bytes)");
    }
    done += static_cast<std::size_t>(got);
  }
  return FileBytes(std::move(data), bytes);
}

}  // namespace detail

std::string read_input_file(const std::string& path) {
  const detail::FileBytes bytes = detail::read_file_bytes(path);
  return std::string(bytes.view());
}

}  // namespace conform
