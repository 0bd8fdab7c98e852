#!/usr/bin/env bash
# Benchmarks; figures go to bench/ (JSON and a Markdown table).
# Usage: scripts/bench.sh fluid|structure|coupling|fsi|wcsph [--quick]
#   fluid: 2D dam break at L0 0.01 and 0.005 m (2 s, and 0.6 s to the far-wall impact), 3D tank >= 100k
#          particles, 1 vs 2 ranks
#          (--quick: a coarse dam break that runs in minutes on 2 cores; --case NAME, --ranks 1,2:
#          a part of the set, its rows replacing the same rows in bench/fluid_figures.*)
#   structure: the paper's tank mesh (cases/tank3d_dry, ~56k equations) on 1 and 2 ranks:
#          assembly, factorisation, time per Newmark step, 20-mode modal time, peak memory
#          (--quick: the coarse twin)
#   coupling: the solver dummies with 10k and 100k interface vertices at 1:1 and 2:2 ranks,
#          parallel staggered and implicit IQN-ILS: time per window, share of time in the coupling
#          (--quick: 10k vertices, 1:1)
#   fsi: the coupled pair on the elastic plate (aluminium, and ten times denser), explicit and
#          implicit, and on the flexible cylinder, both staggered schemes with the added-mass
#          operator: share of wall time in the fluid, the structure, waiting for the partner and
#          coupling work (--quick: the plate, implicit)
#   wcsph: the reference the fluid benchmark is judged against: a weakly-compressible SPH code
#          (PySPH, installed by scripts/setup.sh bench) on the same dam break, L0 0.01 m, 0.6 s (the
#          fluid set's dam_break_2d_front), on 2 threads: its steps, wall time, particle-steps/s and
#          surge front (--spacing, --end-time, --threads to change them)
set -euo pipefail
source "$(dirname "$0")/common.sh"
what=${1:-fluid}
shift || true
bash "$repo_root/scripts/build.sh" release
cd "$repo_root"
case "$what" in
  fluid) /usr/bin/python3 scripts/bench/fluid_bench.py --solver build/bin/sph_solver --output bench "$@" ;;
  structure) /usr/bin/python3 scripts/bench/structure_bench.py --solver build/bin/fem_solver --output bench "$@" ;;
  coupling) /usr/bin/python3 scripts/bench/coupling_bench.py --dummy build/bin/solver_dummy --output bench "$@" ;;
  fsi) /usr/bin/python3 scripts/bench/fsi_bench.py --output bench "$@" ;;
  wcsph) bash scripts/setup.sh bench && /usr/bin/python3 scripts/bench/wcsph_reference.py --output bench "$@" ;;
  *) echo "bench.sh: unknown benchmark '$what' (known: fluid, structure, coupling, fsi, wcsph)" >&2; exit 2 ;;
esac
