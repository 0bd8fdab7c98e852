#!/usr/bin/env bash
# Configures and builds tankfsi. Usage: scripts/build.sh [release|debug|asan|fuzz]
# release builds into build/, debug into build-debug/, asan into build-asan/,
# fuzz (clang, the fuzz targets only) into build-fuzz/; executables land in
# <build folder>/bin/. Under CI (CI=true) warnings are errors.
set -euo pipefail
source "$(dirname "$0")/common.sh"
preset=${1:-release}
options=()
# Only CI sets the option: flipping it on every build would rebuild everything.
[[ "${CI:-}" == "true" ]] && options+=(-DTANKFSI_WERROR=ON)
cd "$repo_root"
cmake --preset "$preset" "${options[@]}" >/dev/null
cmake --build --preset "$preset" -j "$jobs"
