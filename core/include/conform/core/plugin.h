#pragma once
// Shared libraries conform loads on first use (dlopen), so that heavy dependencies stay out of the start-up path:
// `conform --help` must not bind OpenCASCADE (cad/) or PCL's features (FPFH). A plugin `name` is the file
// lib<name>.so, looked up beside the running executable first, then in the install lib directory.
//
//   const Plugin& cad = Plugin::load("conform_cad");
//   auto* read = cad.symbol<int(const conform_cad_request*, conform_cad_result*)>("conform_cad_read");

#include <string>
#include <utility>

namespace conform {

class Plugin {
 public:
  // Loaded once per process (thread-safe) and never unloaded. Throws conform::Error naming every path tried and
  // dlerror()'s reason when the library cannot be loaded.
  static const Plugin& load(const std::string& name);

  // The exported symbol `name` as a function (or object) of type F. Throws conform::Error naming the library's
  // path and dlerror()'s reason when the library does not export it.
  template <class F>
  F* symbol(const char* name) const {
    return reinterpret_cast<F*>(raw_symbol(name));
  }

  const std::string& path() const { return path_; }

 private:
  Plugin(std::string path, void* handle) : path_(std::move(path)), handle_(handle) {}
  void* raw_symbol(const char* name) const;

  std::string path_;
  void* handle_ = nullptr;
};

}  // namespace conform
