#!/usr/bin/env bash
# Configures and builds tankfsi. Usage: scripts/build.sh [release|debug|asan]
# release builds into build/, debug into build-debug/, asan into build-asan/;
# executables land in <build folder>/bin/. Under CI (CI=true) warnings are errors.
set -euo pipefail
source "$(dirname "$0")/common.sh"
preset=${1:-release}
werror=OFF
[[ "${CI:-}" == "true" ]] && werror=ON
cd "$repo_root"
cmake --preset "$preset" -DTANKFSI_WERROR=$werror >/dev/null
cmake --build --preset "$preset" -j "$jobs"
