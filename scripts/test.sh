#!/usr/bin/env bash
# Sets up the machine, builds, and runs every test CI runs (labels unit,
# integration, validation). Usage: scripts/test.sh [release|debug|asan] [ctest args...]
set -euo pipefail
source "$(dirname "$0")/common.sh"
preset=${1:-release}
shift || true
bash "$repo_root/scripts/setup.sh"
bash "$repo_root/scripts/build.sh" "$preset"
cd "$repo_root"
ctest --preset "$preset" -j "$jobs" -L 'unit|integration|validation' "$@"
