#include "conform/core/plugin.h"

#include <dlfcn.h>
#include <unistd.h>

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "conform/core/error.h"

#ifndef CONFORM_INSTALL_LIBDIR
#define CONFORM_INSTALL_LIBDIR "/usr/local/lib"
#endif

namespace conform {

namespace {

// The directory of the running executable (/proc/self/exe), "" when unknown.
std::string executable_dir() {
  std::vector<char> buffer(4096);
  const ssize_t n = ::readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
  if (n <= 0) return "";
  const std::string path(buffer.data(), static_cast<std::size_t>(n));
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash);
}

std::string dl_reason() {
  const char* reason = ::dlerror();
  return reason != nullptr ? reason : "unknown reason";
}

}  // namespace

const Plugin& Plugin::load(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<Plugin>> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  if (const auto it = loaded.find(name); it != loaded.end()) return *it->second;

  const std::string file = "lib" + name + ".so";
  std::vector<std::string> candidates;
  const std::string beside = executable_dir();
  if (!beside.empty()) candidates.push_back(beside + "/" + file);
  candidates.push_back(std::string(CONFORM_INSTALL_LIBDIR) + "/" + file);
  std::string tried;
  for (const std::string& path : candidates) {
    if (::access(path.c_str(), F_OK) != 0) {
      tried += "\n  " + path + ": no such file";
      continue;
    }
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      throw Error("cannot load the plugin " + path + ": " + dl_reason());
    }
    auto& slot = loaded[name];
    slot.reset(new Plugin(path, handle));
    return *slot;
  }
  throw Error("the plugin " + file + " was not found; looked for it in" + tried +
              "\n(it is built with the conform program: rebuild, or reinstall conform)");
}

void* Plugin::raw_symbol(const char* name) const {
  ::dlerror();
  void* address = ::dlsym(handle_, name);
  if (address == nullptr) {
    throw Error("the plugin " + path_ + " does not export " + name + ": " + dl_reason());
  }
  return address;
}

}  // namespace conform
