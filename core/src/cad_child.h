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
// as they were. glibc's fork resets malloc's arenas and the dynamic loader's lock for the child, which is what the
// child uses (malloc, dlopen of the plugin, OpenCASCADE's allocator on malloc); it never touches OpenMP, Python or
// any lock of conform's other than Plugin::load's, which the parent never takes for the cad plugin (only children
// load it). The same pattern (fork, then dlopen and malloc in the child) is what multiprocessing's "fork" start and
// many crash-isolating test runners rely on. The child ends with _exit(): no atexit handler, no stdio flush of the
// parent's buffers, no destructor of state it shares with the parent.

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
