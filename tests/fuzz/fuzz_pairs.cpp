// libFuzzer harness: the point-pairs file of `conform align --pairs` (tests/fuzz/README.md).
#include "align/align_inputs.h"
#include "conform/core/error.h"
#include "fuzz_input.h"

CONFORM_FUZZ_READER(".txt", conform::detail::read_point_pairs(path, 1.0))
