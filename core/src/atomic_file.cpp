#include "conform/core/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <string>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "conform/core/error.h"
#include "conform/core/output_set.h"
#include "output_paths.h"
#include "stale_temporaries.h"

namespace conform {

namespace {

constexpr int kTempAttempts = 100;

// A new temporary beside `target`: O_EXCL|O_NOFOLLOW, so that nothing planted at its name (a file, a symlink) is
// ever opened; a random name, retried on a collision; locked until it is renamed or removed (stale_temporaries.h),
// after the leftovers of killed writers in the same directory are removed.
int create_temporary(const std::string& shown, const std::string& target, std::string& temp_path) {
  detail::remove_stale_temporaries(detail::directory_of(target));
  struct stat st {};
  const bool exists = ::stat(target.c_str(), &st) == 0;
  // A new file gets 0666 less the umask, like any other program's output; a replaced one keeps its permission bits.
  const mode_t mode = exists ? static_cast<mode_t>(st.st_mode & 0777) : 0666;
  for (int attempt = 0; attempt < kTempAttempts; ++attempt) {
    temp_path = detail::sibling_name(target, ".conform-tmp-");
    const int fd =
        ::open(temp_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, exists ? 0600 : mode);
    if (fd >= 0) {
      if (!detail::lock_new_temporary(fd, temp_path)) {
        ::close(fd);  // taken for a leftover by another process's sweep in the instant before the lock: another name
        continue;
      }
      if (exists && ::fchmod(fd, mode) != 0) {
        const std::string reason = detail::errno_text();
        ::close(fd);
        ::unlink(temp_path.c_str());
        throw Error(shown + ": cannot set the permissions of its temporary file (" + reason + ")");
      }
      return fd;
    }
    if (errno != EEXIST) break;
  }
  throw Error(shown + ": cannot open for writing (" + detail::errno_text() + ")");
}

// The descriptor an output path names, or -1: `-` and /dev/stdout are 1, /dev/stderr 2, /dev/fd/N and
// /proc/self/fd/N are N. Written through a duplicate of it (same offset, same append mode as the shell set up), never
// reopened or replaced: `--out /dev/stdout > file` appends to what the shell opened, like `>` does for any program.
int inherited_descriptor(const std::string& path) {
  if (path == "-" || path == "/dev/stdout") return STDOUT_FILENO;
  if (path == "/dev/stderr") return STDERR_FILENO;
  for (const std::string prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    if (path.size() > prefix.size() && path.compare(0, prefix.size(), prefix) == 0 &&
        path.find_first_not_of("0123456789", prefix.size()) == std::string::npos && path.size() - prefix.size() < 9) {
      return std::stoi(path.substr(prefix.size()));
    }
  }
  return -1;
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  if (path_.empty()) throw Error("an output path is empty");
  const int inherited = inherited_descriptor(path_);
  struct stat st {};
  if (inherited >= 0) {
    direct_ = true;
    temp_path_ = path_ == "-" ? "/dev/stdout" : path_;
    fd_ = ::fcntl(inherited, F_DUPFD_CLOEXEC, 0);
    if (fd_ < 0) throw Error(path_ + ": cannot write to this descriptor (" + detail::errno_text() + ")");
    return;
  }
  if (::stat(path_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) throw Error(path_ + ": is a directory, not a file to write");
    direct_ = true;  // a device or FIFO: streamed into, never replaced
    temp_path_ = path_;
    fd_ = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
    if (fd_ < 0) throw Error(path_ + ": cannot open for writing (" + detail::errno_text() + ")");
    return;
  }
  target_ = detail::resolve_symlinks(path_);
  fd_ = create_temporary(path_, target_, temp_path_);
}

AtomicFile::~AtomicFile() {
  if (!done_ && !direct_) ::unlink(temp_path_.c_str());  // while still locked, so no sweep can see it unlocked
  close_fd();
}

void AtomicFile::close_fd() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void AtomicFile::write(const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw Error(path_ + ": write failed (" + detail::errno_text() + ")");
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

void AtomicFile::commit() {
  if (done_) return;
  if (direct_) {
    close_fd();
    done_ = true;
    return;
  }
  // On disk before it gets the target's name: a crash after the rename must not leave an empty or torn file. The
  // descriptor stays open (and the temporary locked) until the rename.
  if (::fsync(fd_) != 0) throw Error(path_ + ": write failed (" + detail::errno_text() + ")");
  if (OutputSet* set = OutputSet::current()) {
    set->stage(path_, target_, temp_path_, fd_);  // the set owns the temporary and its descriptor from here
    fd_ = -1;
    done_ = true;
    return;
  }
  if (std::rename(temp_path_.c_str(), target_.c_str()) != 0) {
    throw Error(path_ + ": cannot write (" + detail::errno_text() + ")");
  }
  done_ = true;
  const int status = ::close(fd_);
  fd_ = -1;
  if (status != 0) throw Error(path_ + ": write failed (" + detail::errno_text() + ")");
  detail::fsync_directory(detail::directory_of(target_));
}

void write_file_atomically(const std::string& path, const std::string& contents) {
  AtomicFile file(path);
  file.write(contents.data(), contents.size());
  file.commit();
}

}  // namespace conform
