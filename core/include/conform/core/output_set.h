#pragma once
// All the outputs of one command, committed together: every file is replaced, or none is (docs/foundation.md,
// "Outputs").
//
// A command registers its inputs and outputs before any work: an output that is the same file as an input (same
// device and inode, or the same normalised path once symbolic links are resolved) or that is given twice is refused
// with conform::Error (exit 2) then and there. While the set is current (from construction to destruction, per
// thread), every AtomicFile::commit() hands its finished temporary to the set instead of renaming it; commit() then
// renames them all. The previous version of each target is kept (as a hard link, `NAME.conform-old-<hex>`) until
// every rename has succeeded and is put back if one fails, so a failure never loses a file the set did not create.
// Destroyed without commit(), the set removes its temporaries and leaves every target as it was.
//
// Sets nest: commit() of an inner set (e.g. a pipeline's own) hands its files on to the enclosing set.

#include <string>
#include <vector>

namespace conform {

class OutputSet {
 public:
  OutputSet();
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Empty paths are ignored (an option not given). Throw conform::Error when an output is an input or is given twice.
  void add_input(const std::string& path);
  void add_output(const std::string& path);
  void add_inputs(const std::vector<std::string>& paths);
  void add_outputs(const std::vector<std::string>& paths);

  // Renames every staged temporary over its target, all or none. Throws conform::Error naming the file that failed
  // (every target then as before).
  void commit();

  // The innermost set of this thread, or nullptr.
  static OutputSet* current();
  // AtomicFile::commit(): `temp` (finished, fsync'ed) becomes `target` at commit(). `shown` is the path as the user
  // gave it, for messages. `fd` is the temporary's open descriptor, which holds its lock (stale_temporaries.h); the
  // set closes it once the temporary is renamed or removed (when this throws, both stay the caller's). Throws conform::Error if `target`
  // is already staged or is an input.
  void stage(const std::string& shown, const std::string& target, const std::string& temp, int fd);

  struct FileId {
    std::string shown;
    std::string normal;  // absolute, symbolic links resolved, lexically normal
    bool exists = false;
    bool regular = false;
    unsigned long long device = 0;
    unsigned long long inode = 0;
  };

 private:
  struct Staged {
    std::string shown;
    std::string target;
    std::string temp;
    int fd = -1;  // the temporary's descriptor: its lock
  };
  void check_output(const FileId& output) const;
  void rename_all();
  // Closes every staged descriptor (releasing the temporaries' locks), after removing the temporaries if `remove`.
  void release_staged(bool remove);

  OutputSet* outer_ = nullptr;
  std::vector<FileId> inputs_;
  std::vector<FileId> outputs_;
  std::vector<Staged> staged_;
  bool committed_ = false;
};

}  // namespace conform
