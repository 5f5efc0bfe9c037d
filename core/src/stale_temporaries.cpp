#include "stale_temporaries.h"

#include <cerrno>
#include <cstring>
#include <mutex>
#include <set>

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

namespace conform::detail {

namespace {

constexpr char kTag[] = ".conform-tmp-";
constexpr std::size_t kDigits = 16;

bool same_inode(const struct stat& a, const struct stat& b) { return a.st_dev == b.st_dev && a.st_ino == b.st_ino; }

// Removes `path` if it is a regular file that no process holds locked. The lock is taken on a descriptor of the file
// itself and the name checked again under it, so a file renamed or replaced in between is never removed.
bool remove_if_unlocked(const std::string& path) {
  struct stat by_name {};
  if (::lstat(path.c_str(), &by_name) != 0 || !S_ISREG(by_name.st_mode)) return false;
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return false;
  bool removed = false;
  struct stat by_fd {};
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0 && ::fstat(fd, &by_fd) == 0 && ::lstat(path.c_str(), &by_name) == 0 &&
      same_inode(by_fd, by_name)) {
    removed = ::unlink(path.c_str()) == 0;
  }
  ::close(fd);  // releases the lock
  return removed;
}

}  // namespace

bool is_temporary_name(const std::string& file_name) {
  const std::size_t tag = std::strlen(kTag);
  if (file_name.size() < tag + kDigits) return false;
  const std::size_t at = file_name.size() - kDigits - tag;
  if (file_name.compare(at, tag, kTag) != 0) return false;
  for (std::size_t i = file_name.size() - kDigits; i < file_name.size(); ++i) {
    const char c = file_name[i];
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

bool lock_new_temporary(int fd, const std::string& temp_path) {
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    // Held by a sweep: another name. A file system without locks (some FUSE mounts): written unlocked, and no sweep
    // can take it either, since a sweep removes only what it has locked.
    return errno != EWOULDBLOCK;
  }
  struct stat by_fd {};
  struct stat by_name {};
  return ::fstat(fd, &by_fd) == 0 && by_fd.st_nlink > 0 && ::lstat(temp_path.c_str(), &by_name) == 0 &&
         same_inode(by_fd, by_name);
}

int remove_stale_temporaries(const std::string& directory) {
  static std::mutex mutex;
  static std::set<std::string> swept;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (!swept.insert(directory).second) return 0;
  }
  DIR* dir = ::opendir(directory.c_str());
  if (dir == nullptr) return 0;
  int removed = 0;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (is_temporary_name(name) && remove_if_unlocked(directory + "/" + name)) ++removed;
  }
  ::closedir(dir);
  return removed;
}

}  // namespace conform::detail
