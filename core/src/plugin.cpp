#include "conform/core/plugin.h"

#include <dlfcn.h>
#include <unistd.h>

#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "conform/core/error.h"

#ifndef CONFORM_PLUGIN_INSTALL_DIR
#define CONFORM_PLUGIN_INSTALL_DIR ""
#endif
#ifndef CONFORM_PLUGIN_BUILD_DIR
#define CONFORM_PLUGIN_BUILD_DIR ""
#endif

namespace conform {

namespace {

// The directory of the running executable, "" when /proc is not mounted.
std::string executable_dir() {
  std::vector<char> buffer(4096);
  const ssize_t n = readlink("/proc/self/exe", buffer.data(), buffer.size() - 1);
  if (n <= 0) return "";
  const std::string path(buffer.data(), static_cast<std::size_t>(n));
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? "" : path.substr(0, slash);
}

std::vector<std::string> search_dirs() {
  std::vector<std::string> dirs;
  for (std::string dir : {executable_dir(), std::string(CONFORM_PLUGIN_INSTALL_DIR),
                          std::string(CONFORM_PLUGIN_BUILD_DIR)}) {
    if (dir.empty()) continue;
    bool seen = false;
    for (const std::string& d : dirs) seen = seen || d == dir;
    if (!seen) dirs.push_back(std::move(dir));
  }
  return dirs;
}

}  // namespace

const Plugin& Plugin::load(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<Plugin>> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  auto found = loaded.find(name);
  if (found != loaded.end()) return *found->second;

  const std::string file = "lib" + name + ".so";
  std::string tried;
  for (const std::string& dir : search_dirs()) {
    const std::string path = dir + "/" + file;
    tried += (tried.empty() ? "" : ", ") + path;
    if (access(path.c_str(), F_OK) != 0) continue;
    // RTLD_LOCAL: the module's own copies of conform's code and of its libraries' symbols stay its own.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = dlerror();
      throw Error("cannot load the plugin " + path + ": " + (why != nullptr ? why : "unknown reason") +
                  " (rebuild or reinstall conform)");
    }
    auto plugin = std::unique_ptr<Plugin>(new Plugin(path, handle));
    return *loaded.emplace(name, std::move(plugin)).first->second;
  }
  throw Error("the plugin " + file + " is missing (looked for " + tried +
              "); build the conform target again or reinstall conform");
}

void* Plugin::raw_symbol(const char* name) const {
  dlerror();
  void* address = dlsym(handle_, name);
  if (address == nullptr) {
    const char* why = dlerror();
    throw Error("the plugin " + path_ + " has no symbol " + name + ": " + (why != nullptr ? why : "null address") +
                " (rebuild or reinstall conform)");
  }
  return address;
}

}  // namespace conform
