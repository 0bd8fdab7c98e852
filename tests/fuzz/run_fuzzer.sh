#!/usr/bin/env bash
# Runs one libFuzzer target for TANKFSI_FUZZ_SECONDS (default 20) from its
# corpus folder (libFuzzer adds to it) and read-only seed folders.
# Usage: run_fuzzer.sh BINARY CORPUS ARTIFACT_PREFIX SEED_FOLDER...
set -euo pipefail
binary=$1 corpus=$2 artifacts=$3
shift 3
mkdir -p "$corpus"
exec "$binary" -max_total_time="${TANKFSI_FUZZ_SECONDS:-20}" -seed="${TANKFSI_FUZZ_SEED:-1}" -timeout=10 \
  -rss_limit_mb=4096 -print_final_stats=1 -artifact_prefix="$artifacts" "$corpus" "$@"
