#pragma once
// How long work reports on itself: a callback in its Options, called with a stage name and the fraction done.
// Library code never prints; apps/ decides how to show it.

#include <functional>
#include <string_view>

namespace conform {

// fraction in [0, 1]; called at least at the start (0) and end (1) of every stage, and from one thread only.
using ProgressFn = std::function<void(std::string_view stage, double fraction)>;

inline void report(const ProgressFn& progress, std::string_view stage, double fraction) {
  if (progress) progress(stage, fraction);
}

}  // namespace conform
