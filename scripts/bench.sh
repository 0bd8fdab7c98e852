#!/usr/bin/env bash
# Benchmarks; figures go to bench/ (JSON and a Markdown table).
# Usage: scripts/bench.sh fluid [--quick]
#   fluid: 2D dam break at L0 0.01 and 0.005 m, 3D tank >= 100k particles, 1 vs 2 ranks
#          (--quick: a coarse dam break that runs in minutes on 2 cores)
set -euo pipefail
source "$(dirname "$0")/common.sh"
what=${1:-fluid}
shift || true
bash "$repo_root/scripts/build.sh" release
cd "$repo_root"
case "$what" in
  fluid) /usr/bin/python3 scripts/bench/fluid_bench.py --solver build/bin/sph_solver --output bench "$@" ;;
  *) echo "bench.sh: unknown benchmark '$what' (known: fluid)" >&2; exit 2 ;;
esac
