// libFuzzer harness: conform's CSV tables (trajectories, contours, edges, markers, grids, features) and their
// number cells (tests/fuzz/README.md).
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "fuzz_input.h"

namespace {
double read(const std::string& path) {
  const conform::CsvTable table = conform::read_csv(path);
  double sum = 0.0;
  for (std::size_t r = 0; r < table.rows(); ++r) {
    for (std::size_t c = 0; c < table.columns.size(); ++c) {
      try {
        sum += table.number(r, c) + static_cast<double>(table.integer(r, c));
      } catch (const conform::Error&) {
      }
    }
  }
  return sum;
}
}  // namespace

CONFORM_FUZZ_READER(".csv", read(path))
