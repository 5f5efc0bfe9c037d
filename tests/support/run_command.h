#pragma once
// Runs a program with arguments (no shell), capturing stdout, stderr and the exit status, for end-to-end tests.

#include <string>
#include <vector>

namespace conform::test {

struct RunResult {
  int exit_code = -1;  // the program's exit code; -1 when it did not exit normally
  int signal = 0;      // the signal that ended it (a crash), 0 if none
  std::string out;     // stdout
  std::string err;     // stderr
};

RunResult run(const std::string& program, const std::vector<std::string>& args);

}  // namespace conform::test
