#include "cad_child.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>

#include "conform/core/error.h"
#include "conform/core/plugin.h"

namespace conform::detail {

namespace {

// ---- the child ----------------------------------------------------------------------------------------------------

int g_pipe = -1;                          // the child's write end, for the signal handler
std::uint64_t g_limit_kb = 0;             // the child's address-space limit
char g_status[8192];                      // /proc/self/status, read inside the signal handler (no allocation there)
alignas(16) char g_alt_stack[64 * 1024];  // a stack overflow's SIGSEGV needs a stack of its own

bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

// The peak address space of this process, kB, from /proc/self/status; 0 when unknown. Only open/read and plain
// loops: safe in a signal handler.
std::uint64_t vm_peak_kb() {
  const int fd = ::open("/proc/self/status", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  const ssize_t n = ::read(fd, g_status, sizeof g_status - 1);
  ::close(fd);
  if (n <= 0) return 0;
  g_status[n] = '\0';
  const char* at = std::strstr(g_status, "VmPeak:");
  if (at == nullptr) return 0;
  std::uint64_t kb = 0;
  for (at += 7; *at == ' ' || *at == '\t'; ++at) {
  }
  for (; *at >= '0' && *at <= '9'; ++at) kb = kb * 10 + static_cast<std::uint64_t>(*at - '0');
  return kb;
}

// Tells the parent the signal and how far the peak address space stayed below the limit (so that it can tell a crash
// from an allocation that failed at the memory limit, e.g. OpenCASCADE aborting in a destructor), then dies of the same
// signal (SA_RESETHAND).
void on_fatal_signal(int signal_number) {
  char note[kCadWireHeader + 12];
  const std::uint64_t size = 12;
  const std::int32_t sig = signal_number;
  const std::uint64_t peak = vm_peak_kb();
  const std::uint64_t headroom_kb = peak == 0 ? g_limit_kb : peak > g_limit_kb ? 0 : g_limit_kb - peak;
  note[0] = 'S';
  std::memcpy(note + 1, &size, 8);
  std::memcpy(note + kCadWireHeader, &sig, 4);
  std::memcpy(note + kCadWireHeader + 4, &headroom_kb, 8);
  write_all(g_pipe, note, sizeof note);
  ::raise(signal_number);
}

void install_crash_notes() {
  stack_t stack{};
  stack.ss_sp = g_alt_stack;
  stack.ss_size = sizeof g_alt_stack;
  ::sigaltstack(&stack, nullptr);
  struct sigaction action {};
  action.sa_handler = on_fatal_signal;
  action.sa_flags = SA_RESETHAND | SA_ONSTACK;
  sigemptyset(&action.sa_mask);
  for (const int s : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) ::sigaction(s, &action, nullptr);
}

// The address space the child inherits from its parent, bytes (the limit is counted on top of it: a Python or Dask
// parent may already hold gigabytes, which the child maps but does not add to).
std::uint64_t inherited_address_space() {
  const int fd = ::open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0;
  char text[128] = {};
  const ssize_t n = ::read(fd, text, sizeof text - 1);
  ::close(fd);
  if (n <= 0) return 0;
  return std::strtoull(text, nullptr, 10) * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

void set_limits(const CadReadOptions& options, std::uint64_t* address_space_limit) {
  const rlimit no_core{0, 0};  // a crash on a hostile file is expected here: no core files in the user's directory
  ::setrlimit(RLIMIT_CORE, &no_core);
  *address_space_limit = inherited_address_space() + static_cast<std::uint64_t>(options.memory_limit_mib) * 1024 * 1024;
  g_limit_kb = *address_space_limit / 1024;
  const rlimit memory{*address_space_limit, *address_space_limit};
  ::setrlimit(RLIMIT_AS, &memory);
  // A backstop behind the parent's wall-clock deadline (SIGXCPU at the soft limit), should the parent stop waiting.
  const auto seconds = static_cast<rlim_t>(std::ceil(options.timeout_s)) + 1;
  const rlimit cpu{seconds, seconds + 1};
  ::setrlimit(RLIMIT_CPU, &cpu);
}

void send_progress(void* /*context*/, const char* stage, double fraction) {
  const std::string m = cad_progress_message(stage, fraction);
  write_all(g_pipe, m.data(), m.size());
}

bool mentions_memory(const char* text) { return text != nullptr && std::strstr(text, "memory") != nullptr; }

// Never returns. Everything the parent learns comes through the pipe; the exit status only says whether it got there.
struct PluginFunctions {
  conform_cad_read_fn read;
  conform_cad_free_fn free_result;
};

[[noreturn]] void child_main(int fd, pid_t parent, conform_cad_request request, const CadReadOptions& options,
                             PluginFunctions plugin) {
  // Only stdin, stdout, stderr and the pipe stay open (as fd 3): another thread's read_cad in the parent would
  // otherwise see the end of its own pipe only when this child exits, and OpenCASCADE has no business with the
  // parent's files.
  if (fd != 3 && ::dup2(fd, 3) < 0) ::_exit(5);
  fd = 3;
  ::close_range(4, ~0u, 0);
  g_pipe = fd;
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive a parent that was killed
  if (::getppid() != parent) ::_exit(3);
  ::signal(SIGPIPE, SIG_IGN);  // a parent gone: writes fail, the child exits
  install_crash_notes();
  std::uint64_t limit_bytes = 0;
  set_limits(options, &limit_bytes);
  std::string out;
  try {
    request.progress = send_progress;
    request.progress_context = nullptr;
    conform_cad_result result{};
    if (plugin.read(&request, &result) == 0) {
      out = cad_result_message(result);
    } else {
      const char* text = result.error != nullptr ? result.error : "the CAD plugin failed without a reason";
      // Near the limit, a failure is the limit's doing whatever OpenCASCADE called it.
      const bool at_limit = vm_peak_kb() * 1024 + (64u << 20) >= limit_bytes;
      out = cad_error_message(mentions_memory(text) || at_limit ? CadChildError::kMemory : CadChildError::kRead, text);
    }
    plugin.free_result(&result);
  } catch (const std::bad_alloc&) {
    out = cad_error_message(CadChildError::kMemory, "out of memory");
  } catch (const std::exception& e) {
    out = cad_error_message(CadChildError::kLoad, e.what());
  }
  ::_exit(write_all(fd, out.data(), out.size()) ? 0 : 4);
}

// ---- the parent ---------------------------------------------------------------------------------------------------

// Kills and reaps the child unless it was reaped: no zombie and no orphan, whatever the parent throws (a progress
// callback may throw too).
class Child {
 public:
  explicit Child(pid_t pid) : pid_(pid) {}
  ~Child() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  // The exit status; -1 when it was lost (someone else reaped the child).
  int wait() {
    int status = 0;
    pid_t r = 0;
    while ((r = ::waitpid(pid_, &status, 0)) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    return r < 0 ? -1 : status;
  }
  void kill() const { ::kill(pid_, SIGKILL); }

 private:
  pid_t pid_;
};

class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  ~Fd() { reset(); }
  void reset() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

std::string signal_name(int s) {
  const char* abbrev = sigabbrev_np(s);
  return abbrev != nullptr ? std::string("SIG") + abbrev : "signal " + std::to_string(s);
}

std::string mib_text(std::size_t mib) { return std::to_string(mib) + " MiB"; }

std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", s);
  return text;
}

// What the parent collected from the pipe.
struct Received {
  std::string result;  // an 'R' payload
  bool has_result = false;
  bool has_error = false;
  CadChildError error_category = CadChildError::kRead;
  std::string error;
  int crash_signal = 0;
  std::uint64_t crash_headroom_kb = 0;  // how far below its memory limit the child's peak stayed
};

// Takes the complete messages at the front of `buffer`; throws when one is malformed.
void take_messages(const std::string& path, std::string& buffer, std::size_t max_result_bytes,
                   const ProgressFn& progress, Received& got) {
  std::size_t at = 0;
  while (buffer.size() - at >= kCadWireHeader) {
    const char kind = buffer[at];
    std::uint64_t size = 0;
    std::memcpy(&size, &buffer[at + 1], sizeof size);
    const std::uint64_t limit = kind == 'R' ? max_result_bytes : kind == 'S' ? 12 : 1u << 16;
    if ((kind != 'P' && kind != 'R' && kind != 'E' && kind != 'S') || size > limit) {
      throw Error(path + ": the CAD reader sent a malformed message (kind " + std::to_string(int(kind)) + ", " +
                  std::to_string(size) + " bytes)");
    }
    if (buffer.size() - at - kCadWireHeader < size) break;
    const char* payload = &buffer[at + kCadWireHeader];
    if (kind == 'P') {
      double fraction = 0.0;
      if (size >= sizeof fraction) std::memcpy(&fraction, payload, sizeof fraction);
      const std::string stage(payload + sizeof fraction, size >= sizeof fraction ? size - sizeof fraction : 0);
      // Only the two stages the plugin reports, with a fraction in [0, 1], reach the caller's callback.
      if ((stage == "read CAD" || stage == "tessellate CAD") && fraction >= 0.0 && fraction <= 1.0) {
        report(progress, stage, fraction);
      }
    } else if (kind == 'R') {
      got.result.assign(payload, size);
      got.has_result = true;
    } else if (kind == 'E' && size >= 1) {
      got.has_error = true;
      got.error_category = static_cast<CadChildError>(payload[0]);
      got.error.assign(payload + 1, size - 1);
    } else if (kind == 'S' && size == 12) {
      std::memcpy(&got.crash_signal, payload, 4);
      std::memcpy(&got.crash_headroom_kb, payload + 4, 8);
    }
    at += kCadWireHeader + size;
  }
  buffer.erase(0, at);
}

// Reads the pipe until the child closes it or the deadline passes (then kills it and throws).
Received collect(const std::string& path, int fd, Child& child, const CadReadOptions& options,
                 std::size_t max_result_bytes) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(options.timeout_s);
  Received got;
  std::string buffer;
  char chunk[1 << 16];
  for (;;) {
    const double left_ms = std::chrono::duration<double, std::milli>(deadline - Clock::now()).count();
    pollfd p{fd, POLLIN, 0};
    const int ready = left_ms <= 0.0 ? 0 : ::poll(&p, 1, static_cast<int>(std::ceil(std::min(left_ms, 1e9))));
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      child.kill();
      child.wait();
      throw Error(path + ": the CAD reader took longer than " + seconds_text(options.timeout_s) +
                  " and was stopped (a damaged file, or a part too large for the deflection: raise --cad-timeout or "
                  "use a coarser --cad-deflection)");
    }
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file (or an error): the child is done or dead
    buffer.append(chunk, static_cast<std::size_t>(n));
    take_messages(path, buffer, max_result_bytes, options.progress, got);
  }
  return got;
}

std::string memory_message(const std::string& path, const CadReadOptions& options) {
  return path + ": the CAD reader exceeded the memory limit of " + mib_text(options.memory_limit_mib) +
         " (a damaged file, or a tessellation too fine for the part: use a coarser --cad-deflection or raise "
         "--cad-memory-mib)";
}

}  // namespace

CadWireResult read_cad_in_child(const std::string& path, const conform_cad_request& request,
                                const CadReadOptions& options) {
  // Loaded (once per process) and resolved here, before the fork: the child inherits the mapping and takes no lock
  // and no loader call of its own, and a process reading many files loads OpenCASCADE's libraries once, not per file
  // (90-136 ms each, docs/cad.md). Loading runs only OpenCASCADE's static initialisers in this process, never its
  // reading code.
  const Plugin& loaded = Plugin::load("conform_cad");
  const PluginFunctions plugin{
      loaded.symbol<int(const conform_cad_request*, conform_cad_result*)>("conform_cad_read"),
      loaded.symbol<void(conform_cad_result*)>("conform_cad_free")};
  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0)
    throw Error(path + ": cannot create a pipe for the CAD reader: " + std::strerror(errno));
  Fd read_end(ends[0]), write_end(ends[1]);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw Error(path + ": cannot start the CAD reader process: " + std::strerror(errno));
  if (pid == 0) {
    ::close(ends[0]);
    child_main(ends[1], parent, request, options, plugin);
  }
  Child child(pid);
  write_end.reset();  // the parent sees end of file when the child's end closes
  // A result holds at most max_triangles triangles (12 bytes) with at most 3 vertices each (72 bytes); the rest
  // (bodies, warnings) is small next to the 64 MiB allowed for it.
  const std::size_t max_result_bytes = (std::size_t{64} << 20) + options.max_triangles * 84;
  const Received got = collect(path, read_end.get(), child, options, max_result_bytes);
  const int status = child.wait();

  if (status != -1 && WIFSIGNALED(status)) {
    const int s = WTERMSIG(status);
    if (s == SIGXCPU) {
      throw Error(path + ": the CAD reader took longer than " + seconds_text(options.timeout_s) +
                  " of CPU time and was stopped (raise --cad-timeout or use a coarser --cad-deflection)");
    }
    // A crash within 64 MiB of the limit is put down to it: an allocation failed there and OpenCASCADE, which does
    // not expect that everywhere, fell over (e.g. abort() in a destructor, SIGABRT).
    const bool at_limit = got.crash_signal == s && got.crash_headroom_kb < 65536;
    if (at_limit || (got.has_error && got.error_category == CadChildError::kMemory)) {
      throw Error(memory_message(path, options) + " and crashed (" + signal_name(s) + ")");
    }
    throw Error(path + ": the CAD reader crashed (" + signal_name(s) +
                ") on it: OpenCASCADE cannot read this file (damaged or hostile?); conform itself is unaffected");
  }
  if (got.has_error) {
    if (got.error_category == CadChildError::kMemory) throw Error(memory_message(path, options));
    if (got.error_category == CadChildError::kLoad) throw Error(got.error);
    throw Error(path + ": " + got.error);
  }
  if (!got.has_result) {
    const std::string how =
        status == -1 ? "its exit status was lost" : "it exited with status " + std::to_string(WEXITSTATUS(status));
    throw Error(path + ": the CAD reader ended without a result (" + how + ")");
  }
  CadWireResult out;
  std::string why;
  if (!decode_cad_result(got.result.data(), got.result.size(), options.max_triangles, &out, &why)) {
    throw Error(path + ": the CAD reader sent a malformed result: " + why);
  }
  return out;
}

}  // namespace conform::detail
