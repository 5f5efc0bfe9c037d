// libFuzzer harness: read_cad() on STEP and IGES bytes (issue 32). OpenCASCADE runs in read_cad's child process under
// tight limits, so its crashes, hangs and allocations end there as conform::Error; what this harness can fail on is
// conform's own side: the fork, the pipe, the decoding of an untrusted result, the exit-status mapping (a crash,
// sanitizer report, leak or exception other than conform::Error in this process).
// The child's coverage stays in the child (its counters are copies): libFuzzer steers by the parent's paths only,
// so this is closer to mutation testing of the seeds than to guided fuzzing of OpenCASCADE (tests/fuzz/README.md).
#include <cstring>

#include "conform/core/cad.h"
#include "conform/core/cad_faces.h"
#include "conform/core/error.h"
#include "fuzz_input.h"

namespace {

// Small limits: libFuzzer's own -timeout (10 s in CI) must never see a read, and a run must stay well under its
// -rss_limit_mb (the child's memory is its own, but the result comes back into this process).
conform::CadReadOptions limits() {
  conform::CadReadOptions options;
  options.deflection_mm = 0.05;
  options.timeout_s = 3.0;
  options.memory_limit_mib = 512;
  options.max_triangles = 200'000;
  return options;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static conform::fuzz::ScratchFile step(".step");
  static conform::fuzz::ScratchFile iges(".igs");
  static const conform::CadReadOptions options = limits();
  // The format by the bytes, so that one corpus holds both (the reader checks the signature again).
  const bool is_step = size >= 12 && std::memcmp(data, "ISO-10303-21", 12) == 0;
  const std::string& path = (is_step ? step : iges).write(data, size);
  try {
    conform::CadReport report;
    std::vector<std::string> warnings;
    // read_cad_faces decodes all read_cad does and the faces' section (issue 33) on top.
    (void)conform::read_cad_faces(path, options, &report, &warnings);
  } catch (const conform::Error&) {
  }
  return 0;
}
