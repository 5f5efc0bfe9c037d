// libFuzzer harness: conform's 4x4 transform reader (tests/fuzz/README.md).
#include "conform/core/error.h"
#include "conform/core/transform_io.h"
#include "fuzz_input.h"

CONFORM_FUZZ_READER(".txt", conform::read_transform(path))
