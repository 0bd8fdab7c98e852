# Sourced by the scripts: paths and the MPI environment every run needs.
repo_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# More ranks than cores is allowed; containers often forbid the single-copy path.
export OMPI_MCA_rmaps_base_oversubscribe=1
export OMPI_MCA_btl_vader_single_copy_mechanism=none
# hwloc's OpenCL plugin loads any OpenCL driver installed (pocl: LLVM), which takes
# SIGUSR1 over inside mpirun, and mpirun then no longer forwards it to the ranks
# (the checkpoint-and-stop signal). The solvers need no OpenCL topology.
export HWLOC_COMPONENTS=-opencl
jobs=$(nproc 2>/dev/null || echo 2)
