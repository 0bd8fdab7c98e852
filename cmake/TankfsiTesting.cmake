# Test registration helpers.
#
# tankfsi_add_catch_test(NAME n SOURCES s.cpp... LIBRARIES l... LABELS unit RANKS 1 2 4)
#   builds one Catch2 executable (MPI-aware main, rank 0 prints) and registers one
#   ctest per rank count, run under mpiexec: n.np1, n.np2, n.np4.
#   More ranks than cores is allowed (--oversubscribe): tests check decomposition
#   logic, not speed.
# tankfsi_add_mpi_test(NAME n RANKS 1 2 COMMAND exe args... LABELS l)
#   registers an arbitrary command under mpiexec the same way.

# odls_base_sigkill_timeout=0: mpirun otherwise waits 2 s before tearing down a
# job whose process exited non-zero, which the bad-input tests do by design.
# (Not set for real runs: a job killed by the scheduler needs that grace time.)
# HWLOC_COMPONENTS=-opencl: as scripts/common.sh says, so that mpirun forwards SIGUSR1.
# hwloc_base_binding_policy=none: mpirun binds a job of one or two ranks to the
# first cores, and ctest runs two such jobs at once (-j2): both were bound to
# core 0 and shared it while core 1 idled (two 1-rank unit tests: 54 s
# together, 37 s unbound; the sanitizer build's sph_unit_tests.np1 took 94 s in
# the suite and 35 s alone).
set(TANKFSI_TEST_ENVIRONMENT
  OMPI_ALLOW_RUN_AS_ROOT=1
  OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  OMPI_MCA_rmaps_base_oversubscribe=1
  OMPI_MCA_btl_vader_single_copy_mechanism=none
  OMPI_MCA_odls_base_sigkill_timeout=0
  OMPI_MCA_hwloc_base_binding_policy=none
  HWLOC_COMPONENTS=-opencl
  TANKFSI_PYTHON=${TANKFSI_PYTHON})

# Sanitizer builds: address and undefined-behaviour errors stop the test
# (halt_on_error). Leak checking is off: Open MPI 4.1 dlclose()s its plug-ins
# before LeakSanitizer runs, so their process-lifetime allocations show as
# <unknown module> frames that no suppression can name, and every MPI test
# would fail on them. Our code owns memory through RAII containers only.
if(TANKFSI_SANITIZE)
  list(APPEND TANKFSI_TEST_ENVIRONMENT
    ASAN_OPTIONS=detect_leaks=0:halt_on_error=1:abort_on_error=0
    UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1)
endif()

function(tankfsi_add_mpi_test)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "RANKS;COMMAND;LABELS" ${ARGN})
  if(NOT T_RANKS)
    set(T_RANKS 1)
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 300)
  endif()
  foreach(np IN LISTS T_RANKS)
    set(test_name ${T_NAME}.np${np})
    add_test(NAME ${test_name}
      COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${np} --oversubscribe ${T_COMMAND})
    set(processors ${np})
    if(processors GREATER 2)
      set(processors 2)
    endif()
    set_tests_properties(${test_name} PROPERTIES
      LABELS "${T_LABELS}" PROCESSORS ${processors} TIMEOUT ${T_TIMEOUT}
      ENVIRONMENT "${TANKFSI_TEST_ENVIRONMENT}")
  endforeach()
endfunction()

# Test cases tagged [heavy] are numerical checks that take 0.12-1.9 s
# uninstrumented and 3.6-12.5 s under the sanitizers (6 to 42 times as long), on
# code paths that smaller cases take too (the elastica and the swinging cantilever beside
# the circular arc and the small co-rotational motion; the synthetic
# spectrum's fit beside its reproducibility and scaling; the cylindrical
# tank's added mass beside the side wall's; the triangle index against brute
# force on a cylinder beside the icosphere). The sanitizer build leaves them
# to the release build, which runs them on every rank count. (Instrumented,
# the unit tests on 1 and 2 ranks summed 188 s in the suite with them, and
# 91 s run by themselves without.)
function(tankfsi_add_catch_test)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "SOURCES;LIBRARIES;LABELS;RANKS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE tankfsi_catch_main ${T_LIBRARIES} tankfsi_warnings)
  set_target_properties(${T_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  set(selection "")
  if(TANKFSI_SANITIZE)
    set(selection "~[heavy]")
  endif()
  tankfsi_add_mpi_test(NAME ${T_NAME} RANKS ${T_RANKS} TIMEOUT ${T_TIMEOUT} LABELS ${T_LABELS}
    COMMAND $<TARGET_FILE:${T_NAME}> --durations no ${selection})
endfunction()
