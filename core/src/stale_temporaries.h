#pragma once
// Temporaries of dead processes (docs/foundation.md, "Outputs"): every AtomicFile holds an exclusive flock(2) on
// its temporary from creation until the temporary is renamed over its target or removed. A temporary whose lock can
// be taken therefore belongs to no living writer: its process was killed (kill -9, power loss) between creating and
// committing it. The next conform process that writes into the same directory removes such leftovers.

#include <string>

namespace conform::detail {

// Takes the lock on a temporary just created with O_EXCL. False when the file is no longer the one the name held
// (a sweeper in another process took it for a leftover in the instant before the lock and removed it): the caller
// closes it and creates another. True also where the file system has no locks (nothing can sweep it there).
bool lock_new_temporary(int fd, const std::string& temp_path);

// Removes every `*.conform-tmp-<16 hex>` regular file in `directory` whose lock can be taken. Once per directory
// per process; best effort (unreadable entries are left alone). Returns how many were removed.
int remove_stale_temporaries(const std::string& directory);

// True for a name of the form `*.conform-tmp-` followed by 16 lower-case hexadecimal digits.
bool is_temporary_name(const std::string& file_name);

}  // namespace conform::detail
