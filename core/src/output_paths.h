#pragma once
// Path helpers for AtomicFile and OutputSet (POSIX): symbolic links resolved, random temporary names, fsync of a
// directory.

#include <string>

namespace conform::detail {

// `path` with symbolic links followed to the file they name (which need not exist). Throws conform::Error after 40
// links (a loop).
std::string resolve_symlinks(const std::string& path);
// The directory holding `path` ("." for a bare name).
std::string directory_of(const std::string& path);
// `length` random hexadecimal digits from getrandom(2) (or /dev/urandom).
std::string random_hex(std::size_t length);
// `target` + `tag` + random digits, the file name cut so that it stays within NAME_MAX.
std::string sibling_name(const std::string& target, const char* tag);
// Best effort: a directory's entries on disk (some file systems refuse; that is not an error).
void fsync_directory(const std::string& directory);
// The text of errno.
std::string errno_text();

}  // namespace conform::detail
