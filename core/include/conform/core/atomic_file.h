#pragma once
// Output that appears whole or not at all (docs/foundation.md, "Outputs").
//
// A regular-file target is written to a temporary created beside it with O_CREAT|O_EXCL|O_NOFOLLOW under a random
// name (`NAME.conform-tmp-<16 hex digits>`), fsync'ed and renamed over the target on commit(); the directory is
// fsync'ed after. An existing target keeps its permission bits. A symlink output path is written through to the file
// it points at (the link stays a link). A device or FIFO (`/dev/null`, `/dev/stdout`) and `-` (standard output) are
// written directly, streaming, with no temporary and no rename. Destroyed without commit() (an exception on the way),
// the temporary is removed and the target is untouched.
//
// While a conform::OutputSet is current (output_set.h), commit() hands the finished temporary to it instead of
// renaming: the set renames all of a command's outputs together, or none.

#include <string>

namespace conform {

class AtomicFile {
 public:
  // Creates the temporary (or opens the device) now. Throws conform::Error naming the path when it cannot.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // As given.
  const std::string& path() const { return path_; }
  // Where to write by name: the temporary, in the target's directory so that the rename is atomic; or, for a
  // device or `-`, the device itself (`/dev/stdout` for `-`).
  const std::string& temp_path() const { return temp_path_; }
  // An open, writable descriptor of temp_path(); owned by this object.
  int fd() const { return fd_; }
  // Writes all of `size` bytes to fd(). Throws conform::Error naming the path (a full disk shows here).
  void write(const char* data, std::size_t size);
  // fsyncs and renames the temporary over the target (or stages it with the current OutputSet). Throws
  // conform::Error naming the path if that fails.
  void commit();

 private:
  void close_fd();

  std::string path_;
  std::string target_;  // path_ with symbolic links resolved: the file that is replaced
  std::string temp_path_;
  int fd_ = -1;
  bool direct_ = false;  // a device, FIFO or `-`: written in place
  bool done_ = false;    // committed or handed over: the destructor leaves temp_path_ alone
};

// Writes `contents` to `path` atomically. Throws conform::Error naming the path when it cannot.
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace conform
