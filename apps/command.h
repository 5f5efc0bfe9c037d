#pragma once
// How a subcommand plugs into `conform`: one file per subcommand, registering itself with CONFORM_COMMAND.
// A command maps its options to a pipeline's Options, runs it and prints the Result; it never holds job logic.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "conform/core/output_set.h"

namespace conform::app {

class Command {
 public:
  virtual ~Command() = default;
  // Declare options on the command's own CLI11 subcommand.
  virtual void configure(CLI::App& command) = 0;
  // Every file the command reads and writes, as given on the command line, before run(): an output that is an input
  // or is given twice is refused here (exit 2, before any work), and every output is committed together after run()
  // (all or none; docs/foundation.md, "Outputs").
  virtual void declare_files(OutputSet& /*files*/) {}
  // Exit code: 0 success, 1 the job ran but did not succeed. Bad input throws conform::Error (exit code 2).
  virtual int run() = 0;
};

struct CommandEntry {
  std::string path;     // "info", or "generate tube" for a command under a group
  std::string summary;  // one line for `conform --help`
  std::function<std::unique_ptr<Command>()> make;
};

std::vector<CommandEntry>& command_registry();

inline bool register_command(CommandEntry entry) {
  command_registry().push_back(std::move(entry));
  return true;
}

}  // namespace conform::app

// CONFORM_COMMAND(InfoCommand, "info", "what a file holds") in the subcommand's .cpp file, inside
// namespace conform::app, after the command class.
#define CONFORM_COMMAND(Type, path, summary)                                                 \
  namespace {                                                                                \
  const bool registered_##Type = ::conform::app::register_command(                           \
      {path, summary, [] { return std::unique_ptr<::conform::app::Command>(new Type()); }}); \
  }
