#pragma once
// The one way conform reads an input file (every reader of core and the jobs' CSV and JSON files go through it):
// only regular files (a symbolic link to one is fine), checked before a byte is read, so that a FIFO cannot hang a job
// and a device (/dev/zero) cannot fill memory; and no larger than kMaxInputFileBytes.

#include <cstdint>
#include <string>

namespace conform {

// 4 GiB: the whole file is held in memory while it is parsed.
constexpr std::uint64_t kMaxInputFileBytes = std::uint64_t{4} << 30;

// The file's bytes. Throws conform::Error naming `path` when it cannot be opened or read (with the system's reason),
// is a directory, FIFO, socket or device, is empty, or is larger than kMaxInputFileBytes.
std::string read_input_file(const std::string& path);

}  // namespace conform
