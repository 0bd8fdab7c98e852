#!/usr/bin/env bash
# Sets up the machine, builds, and runs the tests. What CI runs (.ci/run) is the
# default, "all":
#   release  optimised build, labels unit, integration, validation
#   asan     AddressSanitizer + UndefinedBehaviorSanitizer build, labels unit and
#            sanitize (one integration test of each code path:
#            tests/integration/CMakeLists.txt), the unit tests on 1 and 2 ranks only
#            (their 3- and 4-rank variants run the same code oversubscribed on CI's
#            2 cores, minutes each instrumented; release runs them), without the
#            unit test cases tagged [heavy] (cmake/TankfsiTesting.cmake); the Python
#            post-processing's tests are release's only (no compiled code in them)
#   fuzz     clang libFuzzer targets of the file readers, 20 s each (label fuzz)
# Usage: scripts/test.sh [all|release|debug|asan|fuzz] [ctest args...]
set -euo pipefail
source "$(dirname "$0")/common.sh"
choice=${1:-all}
shift || true
labels_of() {
  case $1 in
    release|debug) echo 'unit|integration|validation' ;;
    asan) echo 'unit|sanitize' ;;
    fuzz) echo 'fuzz' ;;
    *) echo "scripts/test.sh: unknown preset '$1' (all, release, debug, asan, fuzz)" >&2; exit 2 ;;
  esac
}
excluded_names_of() {
  case $1 in
    asan) echo '_unit_tests\.np[34]$' ;;
    *) echo '' ;;
  esac
}
presets=("$choice")
[[ "$choice" == all ]] && presets=(release asan fuzz)
for preset in "${presets[@]}"; do labels_of "$preset" >/dev/null; done
bash "$repo_root/scripts/setup.sh"
cd "$repo_root"
for preset in "${presets[@]}"; do
  echo "== $preset: build"
  bash "$repo_root/scripts/build.sh" "$preset"
  excluded_names=$(excluded_names_of "$preset")
  echo "== $preset: tests ($(labels_of "$preset")${excluded_names:+, not $excluded_names})"
  ctest --preset "$preset" -j "$jobs" -L "$(labels_of "$preset")" ${excluded_names:+-E "$excluded_names"} "$@"
done
