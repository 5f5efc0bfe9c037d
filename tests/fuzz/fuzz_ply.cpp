// libFuzzer harness: conform's .ply reader (tests/fuzz/README.md).
#include "conform/core/error.h"
#include "conform/core/io.h"
#include "fuzz_input.h"

namespace {
conform::Mesh read(const std::string& path) {
  conform::ReadReport report;
  return conform::read_geometry(path, {conform::NonFinitePolicy::kKeep}, &report);
}
}  // namespace

CONFORM_FUZZ_READER(".ply", read(path))
