// Inputs the fuzzer (tests/fuzz) found to break the library, replayed as plain tests
// (hardening). Each test names the reproducer kept in tests/fuzz/regressions/.
#include "drape_test_util.h"

using namespace drape_test;
