#pragma once
// OpenCASCADE in a child process (issue 32): a damaged STEP or IGES file can make it crash (SIGSEGV), grow without
// bound or loop for minutes, and in-process that takes the command line, the Python interpreter or the Dask worker
// with it. read_cad() therefore forks; the child loads the cad plugin, reads and tessellates under an address-space
// limit (RLIMIT_AS), a CPU-time limit and the parent's wall-clock deadline, and sends the mesh back through a pipe
// (cad_wire.h), with progress messages on the way. The parent validates what it receives as untrusted input.
//
// Why fork without exec: the child needs nothing but libc, libstdc++ and the plugin, and the request is already in
// memory; an exec would need a helper executable found at run time and the file's bytes sent over. fork() in a
// process that may have threads (OpenMP, Python, Dask) gives a child with one thread and every other thread's locks
// as they were. The parent therefore loads the plugin and resolves its two functions before forking (the first CAD
// read of the process; conform --help still loads nothing): the child makes no loader call and takes no lock of
// conform's. What it does use is malloc (OpenCASCADE's allocator too), whose arenas glibc's fork resets for the child,
// and the plugin's own code; it never touches OpenMP, Python or Dask. The same pattern (fork, then malloc and library
// code in the child) is what multiprocessing's "fork" start and crash-isolating test runners rely on. The child ends
// with _exit(): no atexit handler, no stdio flush of the parent's buffers, no destructor of state it shares with the
// parent.

#include <cstddef>
#include <string>
#include <vector>

#include "cad_wire.h"
#include "conform/core/cad.h"
#include "conform/core/cad_plugin_abi.h"

namespace conform::detail {

// Runs the plugin's conform_cad_read(request) in a child process under options' limits. Throws conform::Error naming
// `path` when the child crashed (the signal), exceeded the memory limit or the time limit, sent a malformed result,
// or the plugin refused the file (its reason). request.progress is ignored: options.progress receives the child's.
CadWireResult read_cad_in_child(const std::string& path, const conform_cad_request& request,
                                const CadReadOptions& options);

}  // namespace conform::detail
