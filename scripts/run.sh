#!/usr/bin/env bash
# Sets up the machine, builds, and runs a case as a user would.
# Usage: scripts/run.sh [CASE_DIR [--set KEY=VALUE ...]]   (default: the default case below)
# The --set overrides go to the programs, e.g. the coarse twin of the overflow case:
#   scripts/run.sh cases/overflow_2d --set fluid.spacing=0.02 --set fluid.time_step.max=0.002
# Results go to runs/<case>-<date-time>/ (printed at the end).
set -euo pipefail
source "$(dirname "$0")/common.sh"
default_case=cases/tank3d_fixed_roof_coarse
case_dir=${1:-$default_case}
[[ $# -gt 0 ]] && shift
overrides=("$@")
bash "$repo_root/scripts/setup.sh"
bash "$repo_root/scripts/build.sh" release
cd "$repo_root"
case_file="$case_dir/case.yaml"
[[ -f "$case_file" ]] || { echo "run.sh: no case file $case_file" >&2; exit 2; }
run_dir="runs/$(basename "$case_dir")-$(date +%Y%m%d-%H%M%S)"

# A fluid-only case (no structure section) runs sph_solver alone, on all cores.
if ! grep -q '^structure:' "$case_file"; then
  mpirun -np "${TANKFSI_RANKS:-$jobs}" build/bin/sph_solver "$case_file" --output "$run_dir" "${overrides[@]}"
  /usr/bin/python3 scripts/post/plot_probes.py "$run_dir"
  # The paper's §3 outputs of an overflow case: wave height, overflow, periods, pressure maps.
  if grep -q 'type: overflow_tank' "$case_file"; then
    /usr/bin/python3 scripts/post/overflow_figures.py "$run_dir"
  fi
  echo "run.sh: results in $run_dir (open fluid.xdmf and walls.xdmf in ParaView)"
  exit 0
fi

# A structure-only case (no fluid section) runs fem_solver alone, on all cores.
if ! grep -q '^fluid:' "$case_file"; then
  mpirun -np "${TANKFSI_RANKS:-$jobs}" build/bin/fem_solver "$case_file" --output "$run_dir" "${overrides[@]}"
  echo "run.sh: results in $run_dir (open structure.xdmf in ParaView; figures in summary.json)"
  exit 0
fi

# A case with fluid and structure runs the two programs as partners of one
# MPMD job, both writing into the run folder (fluid/, structure/), and the
# tank report follows: plots/*.png and report.md. The fluid gets every core
# (TANKFSI_FLUID_RANKS), the structure one rank beside it
# (TANKFSI_STRUCTURE_RANKS); the structure mostly waits for the fluid.
fluid_ranks=${TANKFSI_FLUID_RANKS:-$jobs}
structure_ranks=${TANKFSI_STRUCTURE_RANKS:-1}
echo "run.sh: coupled run of $case_file: sph_solver on $fluid_ranks rank(s), fem_solver on $structure_ranks"
status=0
mpirun -np "$fluid_ranks" build/bin/sph_solver "$case_file" --output "$run_dir" "${overrides[@]}" : \
       -np "$structure_ranks" build/bin/fem_solver "$case_file" --output "$run_dir" "${overrides[@]}" || status=$?
if [[ $status -ne 0 ]]; then
  echo "run.sh: the coupled run failed (exit status $status); its logs, last good state and what it wrote are in $run_dir" >&2
  exit "$status"
fi
/usr/bin/python3 scripts/post/tank_report.py "$run_dir"
echo "run.sh: report $run_dir/report.md (plots in $run_dir/plots; open $run_dir/fluid/fluid.xdmf and $run_dir/structure/structure.xdmf in ParaView)"
