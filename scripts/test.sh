#!/usr/bin/env bash
# The test job (CI runs exactly this, .ci/run): install dependencies; build Release and run every
# test through ctest; build the asan preset (clang, address and undefined-behaviour sanitizers,
# the libFuzzer targets) and run every test again under the sanitizers; then fuzz each loader
# for a few seconds (scripts/fuzz.sh), failing on any crash, sanitizer report or hang.
#
#   scripts/test.sh            all of the above
#   BOUNCE_TEST_FUZZ_SECONDS   seconds per fuzz target (default 10)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release
cmake --build --preset release
ctest --preset release

cmake --preset asan
cmake --build --preset asan
ctest --preset asan
BOUNCE_FUZZ_BUILD=build/asan bash scripts/fuzz.sh "${BOUNCE_TEST_FUZZ_SECONDS:-10}"
