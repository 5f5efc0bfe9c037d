#pragma once
// Shared modules loaded on first use (dlopen), so that a heavy library (OpenCASCADE for STEP and IGES) costs
// start-up time only in the runs that need it: `conform --help` binds no symbol of theirs.
//
// Plugin::load("conform_cad") opens libconform_cad.so, looked for in this order: beside the executable
// (/proc/self/exe's directory: the build tree's `conform` and an installed one), the install's lib directory
// (CMAKE_INSTALL_PREFIX/lib), then the build tree's top directory (tests, benchmarks and bindings run from it).
// A module is opened once per process (thread-safe) and never closed: its code may have thrown exceptions or
// registered objects that outlive any caller.
// Errors (conform::Error): no such module in any of those directories, or a module or symbol that does not load;
// the message names the paths tried and dlerror()'s reason, and says to rebuild or reinstall conform.

#include <string>
#include <utility>

namespace conform {

class Plugin {
 public:
  // The module lib<name>.so, opened on the first call.
  static const Plugin& load(const std::string& name);

  // The module's function `name` (declared extern "C" there) as a pointer of type F*.
  template <class F>
  F* symbol(const char* name) const {
    return reinterpret_cast<F*>(raw_symbol(name));
  }

  const std::string& path() const { return path_; }

  Plugin(const Plugin&) = delete;
  Plugin& operator=(const Plugin&) = delete;

 private:
  Plugin(std::string path, void* handle) : path_(std::move(path)), handle_(handle) {}
  void* raw_symbol(const char* name) const;

  std::string path_;
  void* handle_ = nullptr;
};

}  // namespace conform
