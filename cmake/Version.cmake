# Version and git commit, recorded in every run's provenance.json.
# Re-evaluated at each configure; scripts/build.sh configures before every build.
execute_process(COMMAND git -C ${PROJECT_SOURCE_DIR} rev-parse HEAD
  OUTPUT_VARIABLE TANKFSI_GIT_COMMIT OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
execute_process(COMMAND git -C ${PROJECT_SOURCE_DIR} status --porcelain --untracked-files=no
  OUTPUT_VARIABLE git_changes OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT TANKFSI_GIT_COMMIT)
  set(TANKFSI_GIT_COMMIT "unknown")
elseif(git_changes)
  string(APPEND TANKFSI_GIT_COMMIT "-modified")
endif()
