#!/usr/bin/env bash
# Installs every system package tankfsi needs (Debian 12 / bookworm).
# Idempotent and non-interactive: when everything is present it only checks and exits.
# Usage: scripts/setup.sh [bench]
#   bench: also the reference code the benchmarks compare with (PySPH, a weakly-compressible
#          SPH code: scripts/bench.sh wcsph); not needed to build, run or test tankfsi.
set -euo pipefail

packages=(
  build-essential gfortran cmake ninja-build git pkg-config
  openmpi-bin libopenmpi-dev
  libeigen3-dev
  petsc-dev slepc-dev            # PETSc 3.18 (hypre, MUMPS inside) and SLEPc
  libopenblas0-serial            # optimised BLAS: Debian then prefers it to the reference BLAS
                                 # (MUMPS' dense kernels: 4x faster factorisation, 1.5-2x faster solves)
  libhdf5-openmpi-dev hdf5-tools # parallel HDF5 (MPI-IO)
  libmetis-dev
  catch2 libyaml-cpp-dev nlohmann-json3-dev
  clang libclang-rt-14-dev       # the fuzz preset: clang and its libFuzzer / sanitizer runtimes
  python3 python3-numpy python3-matplotlib python3-h5py python3-yaml
)
case "${1:-}" in
  "") ;;
  bench) packages+=(python3-pysph) ;;
  *) echo "setup.sh: unknown option '$1' (none, or bench)" >&2; exit 2 ;;
esac

if ! command -v apt-get >/dev/null 2>&1 || ! command -v dpkg-query >/dev/null 2>&1; then
  echo "setup.sh: this system has no apt/dpkg. tankfsi's set-up script supports Debian 12" >&2
  echo "and derivatives. Install by hand: ${packages[*]}" >&2
  exit 1
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "setup.sh: all ${#packages[@]} packages present"
  exit 0
fi

as_root=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null 2>&1 || { echo "setup.sh: not root and no sudo; run as root" >&2; exit 1; }
  as_root=(sudo)
fi

echo "setup.sh: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -q
"${as_root[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
echo "setup.sh: done"
