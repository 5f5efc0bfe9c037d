#include "conform/core/output_set.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <set>
#include <utility>

#include <sys/stat.h>
#include <unistd.h>

#include "conform/core/error.h"
#include "output_paths.h"

namespace conform {

namespace {

namespace fs = std::filesystem;

thread_local OutputSet* current_set = nullptr;

OutputSet::FileId identify(const std::string& path) {
  OutputSet::FileId id;
  id.shown = path;
  if (path == "-") {
    id.normal = "-";
    return id;
  }
  const std::string resolved = detail::resolve_symlinks(path);
  std::error_code error;
  fs::path absolute = fs::absolute(resolved, error);
  if (error) absolute = resolved;
  // Every directory on the way resolved too: `x.ply` and `selfdir/x.ply` (selfdir a link to .) are one new file.
  std::error_code canonical_error;
  const fs::path canonical = fs::weakly_canonical(absolute, canonical_error);
  id.normal = (canonical_error ? absolute.lexically_normal() : canonical).string();
  struct stat st {};
  if (::stat(resolved.c_str(), &st) == 0) {
    id.exists = true;
    id.regular = S_ISREG(st.st_mode);
    id.device = static_cast<unsigned long long>(st.st_dev);
    id.inode = static_cast<unsigned long long>(st.st_ino);
  }
  return id;
}

bool same_file(const OutputSet::FileId& a, const OutputSet::FileId& b) {
  if (a.exists && b.exists) return a.device == b.device && a.inode == b.inode;
  return a.normal == b.normal;
}

// A device such as /dev/null may take any number of outputs; a file or standard output only one.
bool shareable(const OutputSet::FileId& output) { return output.exists && !output.regular && output.normal != "-"; }

// The previous version of `target` kept under a new name (a hard link: the target itself is never absent), or ""
// when there is none. Falls back to renaming it aside on file systems without hard links.
std::string keep_previous(const std::string& shown, const std::string& target) {
  struct stat st {};
  if (::lstat(target.c_str(), &st) != 0) return "";
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string backup = detail::sibling_name(target, ".conform-old-");
    if (::link(target.c_str(), backup.c_str()) == 0) return backup;
    if (errno == EEXIST) continue;
    if (std::rename(target.c_str(), backup.c_str()) == 0) return backup;
    break;
  }
  throw Error(shown + ": cannot keep its previous version while writing (" + detail::errno_text() + ")");
}

// Refuses, before any work, an output that cannot be written: a directory, or a file in a directory that does not
// exist or may not be written (the temporary and the rename need the directory).
void check_writable(const OutputSet::FileId& output) {
  if (output.normal == "-") return;
  std::error_code error;
  if (output.exists && fs::is_directory(output.normal, error)) {
    throw Error(output.shown + ": is a directory; give a file name");
  }
  if (shareable(output)) return;
  const fs::path parent = fs::path(output.normal).parent_path();
  if (!fs::is_directory(parent, error)) {
    throw Error(output.shown + ": cannot be written: the directory " + parent.string() + " does not exist");
  }
  if (::access(parent.c_str(), W_OK) != 0) {
    throw Error(output.shown + ": cannot be written: the directory " + parent.string() + " is not writable (" +
                detail::errno_text() + ")");
  }
}

}  // namespace

OutputSet::OutputSet() : outer_(current_set) { current_set = this; }

OutputSet::~OutputSet() {
  current_set = outer_;
  release_staged(!committed_);
}

OutputSet* OutputSet::current() { return current_set; }

void OutputSet::add_input(const std::string& path) {
  if (path.empty() || path == "-") return;
  const FileId input = identify(path);
  for (const FileId& output : outputs_) {
    if (output.regular || !output.exists) {
      if (same_file(input, output)) {
        throw Error(output.shown + ": this output is the input " + path + "; write it to another file");
      }
    }
  }
  inputs_.push_back(input);
}

void OutputSet::add_output(const std::string& path) {
  if (path.empty()) return;
  const FileId output = identify(path);
  check_writable(output);
  check_output(output);
  outputs_.push_back(output);
}

void OutputSet::add_inputs(const std::vector<std::string>& paths) {
  for (const std::string& p : paths) add_input(p);
}

void OutputSet::add_outputs(const std::vector<std::string>& paths) {
  for (const std::string& p : paths) add_output(p);
}

void OutputSet::check_output(const FileId& output) const {
  if (shareable(output)) return;
  for (const FileId& input : inputs_) {
    if (same_file(input, output)) {
      throw Error(output.shown + ": this output is the input " + input.shown + "; write it to another file");
    }
  }
  for (const FileId& other : outputs_) {
    if (same_file(other, output)) {
      const std::string also = other.shown == output.shown ? "" : " (as " + other.shown + ")";
      throw Error(output.shown + ": given as two outputs" + also + "; each output needs its own file");
    }
  }
}

void OutputSet::release_staged(bool remove) {
  for (const Staged& s : staged_) {
    if (remove) ::unlink(s.temp.c_str());  // before the close: a temporary is never seen unlocked by a sweep
    if (s.fd >= 0) ::close(s.fd);
  }
  staged_.clear();
}

void OutputSet::stage(const std::string& shown, const std::string& target, const std::string& temp, int fd) {
  const FileId id = identify(target);
  for (const Staged& s : staged_) {
    if (identify(s.target).normal == id.normal) {
      throw Error(shown + ": written twice (given as two outputs); each output needs its own file");
    }
  }
  for (const FileId& input : inputs_) {
    if (same_file(input, id)) {
      throw Error(shown + ": this output is the input " + input.shown + "; write it to another file");
    }
  }
  staged_.push_back({shown, target, temp, fd});
}

void OutputSet::commit() {
  if (committed_) return;
  if (outer_ != nullptr) {
    // Handed on: the enclosing set commits these with its own. A refusal leaves the rest with this set to remove.
    while (!staged_.empty()) {
      const Staged& s = staged_.front();
      outer_->stage(s.shown, s.target, s.temp, s.fd);
      staged_.erase(staged_.begin());
    }
  } else {
    rename_all();
  }
  committed_ = true;
}

void OutputSet::rename_all() {
  std::vector<std::string> backups(staged_.size());
  std::vector<bool> moved(staged_.size(), false);
  std::size_t i = 0;
  try {
    for (; i < staged_.size(); ++i) {
      backups[i] = keep_previous(staged_[i].shown, staged_[i].target);
      if (std::rename(staged_[i].temp.c_str(), staged_[i].target.c_str()) != 0) {
        throw Error(staged_[i].shown + ": cannot write (" + detail::errno_text() + ")");
      }
      moved[i] = true;
    }
  } catch (...) {
    // Every target back as it was: the previous version restored, or the file this set created removed.
    for (std::size_t k = 0; k <= i && k < staged_.size(); ++k) {
      if (!backups[k].empty()) {
        std::rename(backups[k].c_str(), staged_[k].target.c_str());
        ::unlink(backups[k].c_str());  // still there when the rename was a no-op (two links to one file)
      } else if (moved[k]) {
        ::unlink(staged_[k].target.c_str());
      }
    }
    for (std::size_t k = 0; k < staged_.size(); ++k) {
      if (!moved[k]) ::unlink(staged_[k].temp.c_str());
      if (staged_[k].fd >= 0) ::close(staged_[k].fd);
    }
    staged_.clear();
    throw;
  }
  std::set<std::string> directories;
  for (std::size_t k = 0; k < staged_.size(); ++k) {
    if (!backups[k].empty()) ::unlink(backups[k].c_str());
    directories.insert(detail::directory_of(staged_[k].target));
  }
  for (const std::string& d : directories) detail::fsync_directory(d);
  release_staged(false);
}

}  // namespace conform
