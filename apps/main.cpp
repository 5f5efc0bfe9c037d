// conform: make tool paths fit the part that is really there.
// Parses the command line, runs the chosen subcommand and maps what happened to an exit code (DESIGN.md):
// 0 success, 1 the job ran but did not succeed, 2 bad usage or bad input.

#include <malloc.h>

#include <algorithm>
#include <exception>
#include <iostream>
#include <map>
#include <memory>
#include <new>
#include <stdexcept>

#include <pcl/console/print.h>
#include <CLI/CLI.hpp>

#include "command.h"
#include "terminal.h"
#include "conform/core/error.h"

namespace conform::app {

std::vector<CommandEntry>& command_registry() {
  static std::vector<CommandEntry> registry;
  return registry;
}

namespace {

constexpr int kExitBadInput = 2;

// A job allocates and frees arrays of tens of megabytes many times (trees, surface samples, normals, pairs). By
// default glibc maps each one afresh and returns it on free, so every reuse pays its page faults again (an eighth of
// align's CPU on the bench's mesh pair: docs/measurements/align.md, Speed). Kept in the heap instead, up to glibc's
// largest threshold (32 MiB on 64-bit), freed memory kept for the next array. Outputs are unchanged.
void keep_large_arrays_in_heap() {
  constexpr int kMiB = 1 << 20;
  mallopt(M_MMAP_THRESHOLD, 32 * kMiB);
  mallopt(M_TRIM_THRESHOLD, 256 * kMiB);
  mallopt(M_TOP_PAD, 64 * kMiB);
}

struct Bound {
  CLI::App* app;
  std::unique_ptr<Command> command;
};

// "generate tube" -> a "generate" group holding a "tube" subcommand; groups are made on first use.
CLI::App* subcommand_for(CLI::App& root, const std::string& path, const std::string& summary) {
  CLI::App* parent = &root;
  std::string rest = path;
  for (std::size_t space; (space = rest.find(' ')) != std::string::npos; rest = rest.substr(space + 1)) {
    const std::string group = rest.substr(0, space);
    CLI::App* existing = nullptr;
    for (CLI::App* sub : parent->get_subcommands({})) {
      if (sub->get_name() == group) existing = sub;
    }
    if (existing == nullptr) {
      existing = parent->add_subcommand(group, "");
      existing->require_subcommand(1);
    }
    parent = existing;
  }
  // A group's one-line description lists what it holds, so new members need no edit here.
  if (parent != &root) {
    const std::string listed = parent->get_description();
    parent->description(listed.empty() ? "Subcommands: " + rest : listed + ", " + rest);
  }
  return parent->add_subcommand(rest, summary);
}

}  // namespace
}  // namespace conform::app

int main(int argc, char** argv) {
  using namespace conform::app;
  keep_large_arrays_in_heap();
  // PCL's readers print their own complaints; conform reports errors itself, once, naming the file.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);

  CLI::App root{
      "conform: scan registration and deformation compensation for manufacturing.\n"
      "Lengths are millimetres; flags and JSON keys in degrees say so (_deg).\n"
      "Exit codes: 0 success, 1 the job ran but did not succeed, 2 bad usage or bad input.",
      "conform"};
  root.require_subcommand(1);
  // Every option's default shown in --help is read from the Options struct it is bound to: one source, no
  // hand-written "default N" in a description to drift from the code.
  root.option_defaults()->always_capture_default();
  root.set_version_flag("--version", "conform 0.1.0");

  auto entries = command_registry();
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.path < b.path; });
  std::vector<Bound> bound;
  for (const CommandEntry& entry : entries) {
    CLI::App* app = subcommand_for(root, entry.path, entry.summary);
    bound.push_back({app, entry.make()});
    bound.back().command->configure(*app);
  }

  try {
    root.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = root.exit(e);
    return code == 0 ? 0 : kExitBadInput;
  }

  try {
    for (Bound& b : bound) {
      if (!b.app->parsed()) continue;
      conform::OutputSet outputs;  // every file the command writes is staged here and appears on commit()
      b.command->declare_files(outputs);
      const int code = b.command->run();
      outputs.commit();
      return code;
    }
  } catch (const conform::Error& e) {
    std::cerr << "conform: error: " << printable(e.what()) << std::endl;
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    // The input asks for more memory than the machine has (each reader already refuses counts its file cannot
    // hold): bad input for this machine, not a fault of conform.
    std::cerr << "conform: error: out of memory (the input needs more memory than is available; "
                 "reduce it, e.g. downsample the scan, or run on a larger machine)"
              << std::endl;
    return kExitBadInput;
  } catch (const std::length_error& e) {
    std::cerr << "conform: error: the input asks for more elements than a container can hold (" << printable(e.what())
              << ")" << std::endl;
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "conform: internal error: " << printable(e.what()) << std::endl;
    return 1;
  }
  return kExitBadInput;
}
