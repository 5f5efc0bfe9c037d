#include "terminal.h"

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include <unistd.h>

namespace conform::app {

namespace {
struct ProgressState {
  std::string stage;
  std::chrono::steady_clock::time_point last_draw{};
  bool tty = ::isatty(STDERR_FILENO) != 0;
};
}  // namespace

ProgressFn stderr_progress(bool quiet) {
  if (quiet) return {};
  auto state = std::make_shared<ProgressState>();
  return [state](std::string_view stage, double fraction) {
    const auto now = std::chrono::steady_clock::now();
    if (stage != state->stage) {
      if (state->tty && !state->stage.empty()) std::cerr << '\n';
      state->stage = std::string(stage);
      state->last_draw = now;
      std::cerr << "conform: " << stage << (state->tty ? " ..." : " ...\n") << std::flush;
      return;
    }
    if (!state->tty) return;
    if (fraction < 1.0 && now - state->last_draw < std::chrono::milliseconds(500)) return;
    state->last_draw = now;
    std::cerr << "\rconform: " << stage << " " << static_cast<int>(100.0 * fraction) << "%"
              << (fraction >= 1.0 ? "\n" : "") << std::flush;
    if (fraction >= 1.0) state->stage.clear();
  };
}

void warn(std::string_view message) { std::cerr << "conform: warning: " << message << '\n'; }

void warn_all(const std::vector<std::string>& messages) {
  for (const std::string& m : messages) warn(m);
}

void print_json(const nlohmann::json& object) { std::cout << object.dump(2) << std::endl; }

}  // namespace conform::app
