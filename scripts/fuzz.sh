#!/usr/bin/env bash
# Fuzzes the file readers longer than the tests do (libFuzzer, clang, ASan +
# UBSan): case files, K-NET records, STL and Gmsh meshes.
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET (default 600)] [ctest args, e.g. -R fuzz_stl]
# The corpus grows in build-fuzz/tests/fuzz/corpus/<target> from run to run; a
# finding is saved as build-fuzz/tests/fuzz/<target>-crash-* (reproduce with
# build-fuzz/bin/<target> FILE) and fails that target. Record what was found
# and fixed in tests/fuzz/FINDINGS.md.
set -euo pipefail
source "$(dirname "$0")/common.sh"
export TANKFSI_FUZZ_SECONDS=${1:-600}
shift || true
cd "$repo_root"
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$jobs"
ctest --preset fuzz -j "$jobs" "$@"
