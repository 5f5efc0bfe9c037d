// libFuzzer harness: the features file of `conform profile`, JSON form (tests/fuzz/README.md).
#include "conform/core/error.h"
#include "conform/pipelines/profile/profile.h"
#include "fuzz_input.h"

CONFORM_FUZZ_READER(".json", conform::read_profile_features(path))
